//! Launch times: read from what a user writes (`2020-02-22T13:00Z`) and written back, as
//! seconds since 1970-01-01 00:00 UTC (leap seconds not counted, as every weather file counts
//! them).

use chrono::{DateTime, NaiveDateTime, SecondsFormat, Utc};

/// The rule a launch time keeps, for every message that names it.
pub const LAUNCH_TIME_RULE: &str = "a date and time with its time zone, such as \
    2020-02-22T13:00Z or 2020-02-22T14:00+01:00 (Z: UTC); seconds are optional";

/// Seconds since 1970-01-01 00:00 UTC of a date and time written as ISO 8601 / RFC 3339 with
/// its time zone: `2020-02-22T13:00Z`, `2020-02-22T13:00:30Z`, `2020-02-22 14:00+01:00`,
/// `2020-02-22T13:00:00.5+00:00`. A time without a zone is refused: a weather file's times
/// are UTC and a local time taken for UTC is a silent error of hours.
pub fn parse_utc(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let refuse = || format!("\"{text}\" is not {LAUNCH_TIME_RULE}");
    if t.is_empty() || t.len() > 64 {
        return Err(refuse());
    }
    // The zone: a final 'Z', or a final +HH:MM / -HH:MM (after the date's own dashes).
    let (clock, offset_s) = if let Some(rest) = t.strip_suffix(['Z', 'z']) {
        (rest, 0i64)
    } else {
        let split = t
            .char_indices()
            .rev()
            .find(|&(i, c)| (c == '+' || c == '-') && i > 10)
            .map(|(i, _)| i)
            .ok_or_else(|| {
                format!("\"{text}\" has no time zone: write it as {LAUNCH_TIME_RULE}")
            })?;
        let (clock, zone) = t.split_at(split);
        let sign = if zone.starts_with('-') { -1 } else { 1 };
        let digits = zone[1..].replace(':', "");
        if digits.len() != 4 || !digits.chars().all(|c| c.is_ascii_digit()) {
            return Err(refuse());
        }
        let (h, m): (i64, i64) = (digits[..2].parse().unwrap(), digits[2..].parse().unwrap());
        if h > 23 || m > 59 {
            return Err(refuse());
        }
        (clock, sign * (h * 3600 + m * 60))
    };
    let clock = clock.replacen(' ', "T", 1);
    let naive = ["%Y-%m-%dT%H:%M:%S%.f", "%Y-%m-%dT%H:%M"]
        .iter()
        .find_map(|f| NaiveDateTime::parse_from_str(&clock, f).ok())
        .ok_or_else(refuse)?;
    let utc = naive.and_utc();
    let seconds = utc.timestamp() as f64 + f64::from(utc.timestamp_subsec_nanos()) * 1e-9;
    Ok(seconds - offset_s as f64)
}

/// `seconds` since 1970 UTC written as `2020-02-22T13:00:00Z` (to the second; to the
/// millisecond when it is not a whole second).
pub fn format_utc(seconds: f64) -> String {
    if !seconds.is_finite() {
        return format!("{seconds} s");
    }
    let whole = seconds.floor();
    let nanos = ((seconds - whole) * 1e9).round().min(999_999_999.0) as u32;
    match DateTime::<Utc>::from_timestamp(whole as i64, nanos) {
        Some(t) if nanos == 0 => t.to_rfc3339_opts(SecondsFormat::Secs, true),
        Some(t) => t.to_rfc3339_opts(SecondsFormat::Millis, true),
        None => format!("{seconds} s since 1970"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2020-02-22T13:00Z: 18,314 days after 1970-01-01 (50 years with 12 leap days, then
    /// 31 + 21 days into 2020), then 13 hours.
    const BELLA_LUI_S: f64 = (18_314.0 * 86_400.0) + 13.0 * 3600.0;

    #[test]
    fn a_launch_time_reads_in_every_form_a_user_writes_it_as_the_same_instant() {
        assert_eq!(50 * 365 + 12 + 31 + 21, 18_314);
        for text in [
            "2020-02-22T13:00Z",
            "2020-02-22T13:00:00Z",
            "2020-02-22 13:00z",
            "2020-02-22T14:00+01:00",
            "2020-02-22T08:30-04:30",
            "2020-02-22T14:00:00.000+0100",
            "  2020-02-22T13:00Z ",
        ] {
            assert_eq!(parse_utc(text), Ok(BELLA_LUI_S), "{text}");
        }
        assert_eq!(parse_utc("2020-02-22T13:00:00.25Z"), Ok(BELLA_LUI_S + 0.25));
        assert_eq!(format_utc(BELLA_LUI_S), "2020-02-22T13:00:00Z");
        assert_eq!(format_utc(BELLA_LUI_S + 0.25), "2020-02-22T13:00:00.250Z");
    }

    #[test]
    fn a_launch_time_without_a_zone_or_with_a_bad_field_is_refused_with_the_rule() {
        for text in [
            "2020-02-22T13:00",
            "2020-02-22",
            "13:00Z",
            "2020-02-30T13:00Z",
            "2020-02-22T25:00Z",
            "2020-02-22T13:00+25:00",
            "yesterday",
            "",
        ] {
            let e = parse_utc(text).unwrap_err();
            assert!(e.contains("2020-02-22T13:00Z"), "{text}: {e}");
        }
        assert!(parse_utc("2020-02-22T13:00")
            .unwrap_err()
            .contains("no time zone"));
    }
}
