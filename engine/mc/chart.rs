//! Charts as SVG text: the one place that turns numbers into drawn lines, bands, bars,
//! points, ellipses and axes, for the campaign report and `fly --plot`.
//!
//! Written here rather than through a plotting crate: `plotters`' SVG back end draws in whole
//! pixels (its backend coordinates are `i32`), so an ellipse or a circle is drawn as a
//! polygon quantized to the pixel and a test cannot read a drawn semi-axis back in metres; it
//! has no way to label what it draws (a drawn ellipse cannot carry the values it shows), and
//! it sizes text either by a guess or through the system's font libraries (fontconfig and
//! FreeType at build time). What the report needs is small: linear and logarithmic axes with
//! round ticks, lines, bands, bars, points, ellipses and circles in an equal-aspect frame,
//! labels and a legend. Every drawn element is a plain SVG element with its coordinates to a
//! tenth of a pixel (an ellipse's semi-axes to a thousandth), and the shapes a test checks
//! carry their values in metres as `data-` attributes as well.
//!
//! A chart has a plot area (its scales map data to pixels, y up) inside margins that hold
//! the ticks, the axis labels, the title and the legend; what is drawn in the plot area is
//! clipped to it. The root element carries its scales (`data-x-scale`, `data-y-scale`: the
//! data values at the plot area's two edges and their pixels), so what is drawn can be read
//! back in data units.

use std::fmt::Write as _;

/// The palette: colour-blind-safe (Okabe and Ito's), in the order series take them.
pub const PALETTE: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442",
];
/// Grey of grid lines and frames.
const GRID: &str = "#d9d9d9";
const INK: &str = "#222222";
const MUTED: &str = "#555555";

/// Escape text for XML (element text and attribute values).
pub fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A number for a tick label or a caption: `step` says how many decimals are needed.
pub fn fmt_tick(v: f64, step: f64) -> String {
    let v = if v.abs() < step.abs() * 1e-9 { 0.0 } else { v };
    let a = v.abs().max(step.abs());
    if a != 0.0 && !(1e-4..1e7).contains(&a) {
        return format!("{v:.1e}");
    }
    let decimals = if step > 0.0 {
        (-step.log10().floor()).max(0.0) as usize
    } else {
        0
    };
    // 2.5-type steps need one decimal more than their magnitude says.
    let decimals =
        if step > 0.0 && ((step / 10f64.powi(-(decimals as i32))).fract() - 0.5).abs() < 1e-6 {
            decimals + 1
        } else {
            decimals
        };
    let s = format!("{v:.decimals$}");
    // Thousands separated by a thin space for large round numbers.
    if decimals == 0 && a >= 10_000.0 {
        let neg = s.starts_with('-');
        let digits: Vec<char> = s.trim_start_matches('-').chars().collect();
        let mut out = String::new();
        for (i, c) in digits.iter().enumerate() {
            if i > 0 && (digits.len() - i) % 3 == 0 {
                out.push('\u{2009}');
            }
            out.push(*c);
        }
        return if neg { format!("−{out}") } else { out };
    }
    s.replacen('-', "−", 1)
}

/// Round tick positions (1, 2, 2.5 or 5 × 10ᵏ apart) covering [lo, hi], about `n` of them,
/// and their spacing.
pub fn ticks(lo: f64, hi: f64, n: usize) -> (Vec<f64>, f64) {
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo {
        return (vec![lo], 1.0);
    }
    let raw = (hi - lo) / n.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step - 1e-9).ceil();
    let last = (hi / step + 1e-9).floor();
    let out = (first as i64..=last as i64)
        .map(|k| k as f64 * step)
        .collect();
    (out, step)
}

/// Range [lo, hi] of the finite values, widened by `pad` of its width on each side (a range
/// of one value gets a width of its own).
pub fn extent<'a>(values: impl IntoIterator<Item = &'a f64>, pad: f64) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in values {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if lo > hi {
        return None;
    }
    if hi - lo <= 1e-12 * lo.abs().max(1.0) {
        let w = (lo.abs() * 0.05).max(1e-3);
        return Some((lo - w, hi + w));
    }
    let w = hi - lo;
    Some((lo - pad * w, hi + pad * w))
}

/// A map of data values to pixels along one axis.
#[derive(Debug, Clone, Copy)]
pub struct Scale {
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
    /// Pixels of `lo` and `hi`.
    pub px0: f64,
    pub px1: f64,
}

impl Scale {
    pub fn px(&self, v: f64) -> f64 {
        let f = if self.log {
            (v.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        };
        self.px0 + f * (self.px1 - self.px0)
    }

    /// Pixels per data unit (linear scales).
    pub fn per_unit(&self) -> f64 {
        (self.px1 - self.px0).abs() / (self.hi - self.lo)
    }
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Key {
    Line,
    Dashed,
    Area,
    Dot,
}

/// One SVG chart.
pub struct Chart {
    id: String,
    w: f64,
    h: f64,
    pub x: Scale,
    pub y: Scale,
    title: String,
    x_label: String,
    y_label: String,
    body: String,
    over: String,
    legend: Vec<(String, String, Key)>,
    /// Tick label text for x tick values (categories), in place of numbers.
    x_names: Option<Vec<(f64, String)>>,
    y_names: Option<Vec<(f64, String)>>,
    /// Pixels where something is drawn in the plot area: the legend goes in the corner that
    /// hides the fewest of them.
    ink: Vec<(f64, f64)>,
}

/// Margins around the plot area, px: left, right, top, bottom.
const LEFT: f64 = 64.0;
const RIGHT: f64 = 16.0;
const TOP: f64 = 30.0;
const BOTTOM: f64 = 44.0;

/// A number for an SVG coordinate.
fn c(v: f64) -> String {
    let r = (v * 10.0).round() / 10.0;
    if r == r.trunc() {
        format!("{}", r as i64)
    } else {
        format!("{r:.1}")
    }
}

impl Chart {
    /// A chart `w × h` px of x in [x0, x1] and y in [y0, y1]; `id` names its clip path and
    /// must be unique in the page.
    pub fn new(id: &str, w: f64, h: f64, x: (f64, f64), y: (f64, f64)) -> Chart {
        Chart::with_margins(id, w, h, x, y, LEFT)
    }

    /// [`Chart::new`] with a left margin of `left` px (for long category names).
    pub fn with_margins(
        id: &str,
        w: f64,
        h: f64,
        x: (f64, f64),
        y: (f64, f64),
        left: f64,
    ) -> Chart {
        Chart {
            id: id.to_string(),
            w,
            h,
            x: Scale {
                lo: x.0,
                hi: x.1,
                log: false,
                px0: left,
                px1: w - RIGHT,
            },
            y: Scale {
                lo: y.0,
                hi: y.1,
                log: false,
                px0: h - BOTTOM,
                px1: TOP,
            },
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            body: String::new(),
            over: String::new(),
            legend: vec![],
            x_names: None,
            y_names: None,
            ink: vec![],
        }
    }

    /// A map: east and north in metres at the same scale, the ranges widened to fill the
    /// plot area and to hold `x` and `y`.
    pub fn map(id: &str, w: f64, h: f64, x: (f64, f64), y: (f64, f64)) -> Chart {
        let mut ch = Chart::new(id, w, h, x, y);
        let (pw, ph) = (ch.x.px1 - ch.x.px0, ch.y.px0 - ch.y.px1);
        let per = (pw / (x.1 - x.0)).min(ph / (y.1 - y.0));
        let (cx, cy) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1));
        let (hx, hy) = (0.5 * pw / per, 0.5 * ph / per);
        ch.x.lo = cx - hx;
        ch.x.hi = cx + hx;
        ch.y.lo = cy - hy;
        ch.y.hi = cy + hy;
        ch
    }

    pub fn title(mut self, t: &str) -> Chart {
        self.title = t.to_string();
        self
    }

    pub fn labels(mut self, x: &str, y: &str) -> Chart {
        self.x_label = x.to_string();
        self.y_label = y.to_string();
        self
    }

    /// A logarithmic x axis (the range must be positive).
    pub fn log_x(mut self) -> Chart {
        self.x.log = true;
        self
    }

    /// Category names at x values in place of numeric ticks.
    pub fn x_names(mut self, names: Vec<(f64, String)>) -> Chart {
        self.x_names = Some(names);
        self
    }

    /// Category names at y values in place of numeric ticks.
    pub fn y_names(mut self, names: Vec<(f64, String)>) -> Chart {
        self.y_names = Some(names);
        self
    }

    pub fn px(&self, x: f64, y: f64) -> (f64, f64) {
        (self.x.px(x), self.y.px(y))
    }

    pub fn key(&mut self, label: &str, color: &str, key: Key) {
        self.legend
            .push((label.to_string(), color.to_string(), key));
    }

    /// A line through the points; a non-finite point breaks it.
    pub fn line(&mut self, pts: &[(f64, f64)], color: &str, width: f64, dashed: bool) {
        let mut d = String::new();
        let mut pen = false;
        for &(x, y) in pts {
            if !(x.is_finite() && y.is_finite()) || (self.x.log && x <= 0.0) {
                pen = false;
                continue;
            }
            let (px, py) = self.px(x, y);
            let _ = write!(d, "{}{} {}", if pen { "L" } else { "M" }, c(px), c(py));
            self.ink.push((px, py));
            pen = true;
        }
        if d.is_empty() {
            return;
        }
        let dash = if dashed {
            " stroke-dasharray=\"6 4\""
        } else {
            ""
        };
        let _ = writeln!(
            self.body,
            "<path d=\"{d}\" fill=\"none\" stroke=\"{color}\" stroke-width=\"{width}\" stroke-linejoin=\"round\"{dash}/>"
        );
    }

    /// A band between `lo` and `hi` over `xs` (points where either is not finite break it).
    pub fn band(&mut self, xs: &[f64], lo: &[f64], hi: &[f64], color: &str, opacity: f64) {
        let mut run: Vec<usize> = vec![];
        let flush = |run: &mut Vec<usize>, body: &mut String, ch: &Chart| {
            if run.len() >= 2 {
                let mut d = String::new();
                for (k, &i) in run.iter().enumerate() {
                    let (px, py) = ch.px(xs[i], hi[i]);
                    let _ = write!(d, "{}{} {}", if k == 0 { "M" } else { "L" }, c(px), c(py));
                }
                for &i in run.iter().rev() {
                    let (px, py) = ch.px(xs[i], lo[i]);
                    let _ = write!(d, "L{} {}", c(px), c(py));
                }
                let _ = writeln!(
                    body,
                    "<path d=\"{d}Z\" fill=\"{color}\" fill-opacity=\"{opacity}\" stroke=\"none\"/>"
                );
            }
            run.clear();
        };
        let mut body = std::mem::take(&mut self.body);
        for i in 0..xs.len() {
            for v in [lo[i], hi[i], 0.5 * (lo[i] + hi[i])] {
                if xs[i].is_finite() && v.is_finite() {
                    let p = self.px(xs[i], v);
                    self.ink.push(p);
                }
            }
            if xs[i].is_finite() && lo[i].is_finite() && hi[i].is_finite() {
                run.push(i);
            } else {
                flush(&mut run, &mut body, self);
            }
        }
        flush(&mut run, &mut body, self);
        self.body = body;
    }

    /// A rectangle between data corners.
    pub fn rect(&mut self, x0: f64, x1: f64, y0: f64, y1: f64, fill: &str, opacity: f64) {
        let (a, b) = self.px(x0.min(x1), y0.max(y1));
        let (e, f) = self.px(x0.max(x1), y0.min(y1));
        for i in 0..=2 {
            for j in 0..=2 {
                self.ink
                    .push((a + (e - a) * i as f64 / 2.0, b + (f - b) * j as f64 / 2.0));
            }
        }
        let _ = writeln!(
            self.body,
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{fill}\" fill-opacity=\"{opacity}\"/>",
            c(a),
            c(b),
            c((e - a).max(0.0)),
            c((f - b).max(0.0))
        );
    }

    /// A bar of a histogram: `data` says what it counts (a `data-count` attribute).
    pub fn bar(&mut self, x0: f64, x1: f64, height: f64, fill: &str, count: u64) {
        let (a, b) = self.px(x0, height);
        let (e, f) = self.px(x1, 0.0f64.max(self.y.lo));
        let mut y = b;
        while y < f {
            self.ink.push((0.5 * (a + e), y));
            y += 8.0;
        }
        let _ = writeln!(
            self.body,
            "<rect class=\"bar\" data-count=\"{count}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{fill}\" stroke=\"#ffffff\" stroke-width=\"0.5\"/>",
            c(a),
            c(b),
            c((e - a).max(0.0)),
            c((f - b).max(0.0))
        );
    }

    /// Points (small circles) of radius `r` px.
    pub fn dots(&mut self, pts: &[(f64, f64)], r: f64, color: &str, opacity: f64) {
        if pts.is_empty() {
            return;
        }
        let _ = write!(
            self.body,
            "<g fill=\"{color}\" fill-opacity=\"{opacity}\" stroke=\"none\">"
        );
        for &(x, y) in pts {
            if x.is_finite() && y.is_finite() {
                let (px, py) = self.px(x, y);
                self.ink.push((px, py));
                let _ = write!(
                    self.body,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{r}\"/>",
                    c(px),
                    c(py)
                );
            }
        }
        self.body.push_str("</g>\n");
    }

    /// An ellipse of semi-axes `a` (along `angle_deg`, counterclockwise from +x) and `b` in
    /// data units (an equal-aspect chart), centered at (cx, cy). `class` and the `data-`
    /// attributes name it and carry its values.
    #[allow(clippy::too_many_arguments)]
    pub fn ellipse(
        &mut self,
        (cx, cy): (f64, f64),
        a: f64,
        b: f64,
        angle_deg: f64,
        stroke: &str,
        width: f64,
        dashed: bool,
        class: &str,
    ) {
        let (px, py) = self.px(cx, cy);
        let per = self.x.per_unit();
        let dash = if dashed {
            " stroke-dasharray=\"5 3\""
        } else {
            ""
        };
        // SVG's y points down: a counterclockwise angle in the data is clockwise on screen.
        let _ = writeln!(
            self.body,
            "<ellipse class=\"{class}\" data-semi-major-m=\"{a}\" data-semi-minor-m=\"{b}\" data-angle-deg=\"{angle_deg}\" cx=\"{:.3}\" cy=\"{:.3}\" rx=\"{:.3}\" ry=\"{:.3}\" transform=\"rotate({:.4} {:.3} {:.3})\" fill=\"none\" stroke=\"{stroke}\" stroke-width=\"{width}\"{dash}/>",
            px,
            py,
            a * per,
            b * per,
            -angle_deg,
            px,
            py
        );
    }

    /// A circle of radius `r` in data units (an equal-aspect chart).
    #[allow(clippy::too_many_arguments)]
    pub fn circle(
        &mut self,
        (cx, cy): (f64, f64),
        r: f64,
        stroke: &str,
        width: f64,
        dashed: bool,
        fill: Option<(&str, f64)>,
        class: &str,
    ) {
        let (px, py) = self.px(cx, cy);
        let dash = if dashed {
            " stroke-dasharray=\"2 3\""
        } else {
            ""
        };
        let fill = fill.map_or("fill=\"none\"".to_string(), |(f, o)| {
            format!("fill=\"{f}\" fill-opacity=\"{o}\"")
        });
        let _ = writeln!(
            self.body,
            "<circle class=\"{class}\" data-radius-m=\"{r}\" cx=\"{:.3}\" cy=\"{:.3}\" r=\"{:.3}\" {fill} stroke=\"{stroke}\" stroke-width=\"{width}\"{dash}/>",
            px,
            py,
            r * self.x.per_unit()
        );
    }

    /// A vertical line at x across the plot area, labelled at its top.
    pub fn vline(&mut self, x: f64, color: &str, dashed: bool, label: &str) {
        self.vline_row(x, color, dashed, label, 0);
    }

    /// [`Chart::vline`] with its label on text row `row` from the top (labels of lines close
    /// together on rows of their own).
    pub fn vline_row(&mut self, x: f64, color: &str, dashed: bool, label: &str, row: usize) {
        if !x.is_finite() {
            return;
        }
        let px = self.x.px(x);
        let dash = if dashed {
            " stroke-dasharray=\"4 3\""
        } else {
            ""
        };
        let _ = writeln!(
            self.body,
            "<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"{color}\" stroke-width=\"1.5\"{dash}/>",
            c(px),
            c(self.y.px1),
            c(self.y.px0)
        );
        if !label.is_empty() {
            let inside = px > self.x.px0 && px < self.x.px1;
            if inside {
                let anchor = if px > 0.5 * (self.x.px0 + self.x.px1) {
                    ("end", px - 4.0)
                } else {
                    ("start", px + 4.0)
                };
                let width = 6.0 * label.chars().count() as f64;
                let x0 = if anchor.0 == "end" {
                    anchor.1 - width
                } else {
                    anchor.1
                };
                let y = self.y.px1 + 8.0 + 13.0 * row as f64;
                self.occupy((x0, y), (x0 + width, y + 6.0));
                let _ = writeln!(
                    self.over,
                    "<text x=\"{}\" y=\"{}\" text-anchor=\"{}\" font-size=\"11\" fill=\"{color}\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\">{}</text>",
                    c(anchor.1),
                    c(self.y.px1 + 12.0 + 13.0 * row as f64),
                    anchor.0,
                    esc(label)
                );
            }
        }
    }

    /// A horizontal line at y across the plot area, labelled at its right end.
    pub fn hline(&mut self, y: f64, color: &str, dashed: bool, label: &str) {
        if !y.is_finite() {
            return;
        }
        let py = self.y.px(y);
        let dash = if dashed {
            " stroke-dasharray=\"4 3\""
        } else {
            ""
        };
        let _ = writeln!(
            self.body,
            "<line x1=\"{}\" x2=\"{}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{color}\" stroke-width=\"1.5\"{dash}/>",
            c(self.x.px0),
            c(self.x.px1),
            c(py)
        );
        if !label.is_empty() && py > self.y.px1 && py < self.y.px0 {
            let width = 6.0 * label.chars().count() as f64;
            let mut k = 0.0;
            while k <= width {
                self.ink.push((self.x.px1 - 4.0 - k, py - 8.0));
                k += 6.0;
            }
            let _ = writeln!(
                self.over,
                "<text x=\"{}\" y=\"{}\" text-anchor=\"end\" font-size=\"11\" fill=\"{color}\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\">{}</text>",
                c(self.x.px1 - 4.0),
                c(py - 4.0),
                esc(label)
            );
        }
    }

    /// Text at a data point (clipped with the plot), `anchor` start, middle or end.
    pub fn text(
        &mut self,
        (x, y): (f64, f64),
        dx: f64,
        dy: f64,
        s: &str,
        anchor: &str,
        color: &str,
    ) {
        let (px, py) = self.px(x, y);
        let width = 6.0 * s.chars().count() as f64;
        let start = match anchor {
            "end" => px + dx - width,
            "middle" => px + dx - width / 2.0,
            _ => px + dx,
        };
        let mut k = 0.0;
        while k <= width {
            self.ink.push((start + k, py + dy - 4.0));
            k += 6.0;
        }
        let _ = writeln!(
            self.over,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"{anchor}\" font-size=\"11\" fill=\"{color}\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\">{}</text>",
            c(px + dx),
            c(py + dy),
            esc(s)
        );
    }

    /// Raw SVG drawn above the plot, in pixels (north arrows, scale bars).
    pub fn overlay(&mut self, svg: &str) {
        self.over.push_str(svg);
    }

    /// Mark the pixel box (x0, y0)–(x1, y1) as drawn on, so that the legend keeps off it
    /// (what [`Chart::overlay`] draws).
    pub fn occupy(&mut self, (x0, y0): (f64, f64), (x1, y1): (f64, f64)) {
        let mut y = y0;
        while y <= y1 {
            let mut x = x0;
            while x <= x1 {
                self.ink.push((x, y));
                x += 6.0;
            }
            y += 6.0;
        }
    }

    /// The plot area's corners in pixels: (left, top, right, bottom).
    pub fn area(&self) -> (f64, f64, f64, f64) {
        (self.x.px0, self.y.px1, self.x.px1, self.y.px0)
    }

    /// The chart as an SVG element.
    pub fn svg(&self) -> String {
        let (l, t, r, b) = self.area();
        let mut s = String::with_capacity(self.body.len() + self.over.len() + 4096);
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart\" viewBox=\"0 0 {w} {h}\" width=\"{w}\" height=\"{h}\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"12\" role=\"img\" aria-label=\"{}\" data-x-scale=\"{} {} {} {}\" data-y-scale=\"{} {} {} {}\">",
            esc(&self.title),
            self.x.lo,
            self.x.hi,
            self.x.px0,
            self.x.px1,
            self.y.lo,
            self.y.hi,
            self.y.px0,
            self.y.px1,
            w = self.w,
            h = self.h
        );
        let _ = writeln!(
            s,
            "<rect width=\"{}\" height=\"{}\" fill=\"#ffffff\"/><clipPath id=\"clip-{}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>",
            self.w,
            self.h,
            self.id,
            c(l),
            c(t),
            c(r - l),
            c(b - t)
        );
        // Grid and ticks.
        let mut axes = String::new();
        {
            let xt: Vec<(f64, String)> = match &self.x_names {
                Some(n) => n.clone(),
                None if self.x.log => log_ticks(self.x.lo, self.x.hi),
                None => {
                    let (t, step) = ticks(self.x.lo, self.x.hi, ((r - l) / 55.0).max(2.0) as usize);
                    t.into_iter().map(|v| (v, fmt_tick(v, step))).collect()
                }
            };
            for (v, label) in xt {
                let px = self.x.px(v);
                if px < l - 0.5 || px > r + 0.5 {
                    continue;
                }
                let _ = writeln!(
                    axes,
                    "<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"{GRID}\"/><text x=\"{0}\" y=\"{3}\" text-anchor=\"middle\" fill=\"{MUTED}\">{4}</text>",
                    c(px),
                    c(t),
                    c(b + 4.0),
                    c(b + 17.0),
                    esc(&label)
                );
            }
        }
        {
            let yt: Vec<(f64, String)> = match &self.y_names {
                Some(n) => n.clone(),
                None => {
                    let (tk, step) =
                        ticks(self.y.lo, self.y.hi, ((b - t) / 40.0).max(2.0) as usize);
                    tk.into_iter().map(|v| (v, fmt_tick(v, step))).collect()
                }
            };
            for (v, label) in yt {
                let py = self.y.px(v);
                if py < t - 0.5 || py > b + 0.5 {
                    continue;
                }
                let grid = if self.y_names.is_some() { "none" } else { GRID };
                let _ = writeln!(
                    axes,
                    "<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{grid}\"/><text x=\"{3}\" y=\"{4}\" text-anchor=\"end\" fill=\"{MUTED}\">{5}</text>",
                    c(l - 4.0),
                    c(r),
                    c(py),
                    c(l - 7.0),
                    c(py + 4.0),
                    esc(&label)
                );
            }
        }
        s.push_str(&axes);
        let _ = writeln!(
            s,
            "<g clip-path=\"url(#clip-{})\">\n{}</g>",
            self.id, self.body
        );
        let _ = writeln!(
            s,
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#999999\"/>",
            c(l),
            c(t),
            c(r - l),
            c(b - t)
        );
        s.push_str(&self.over);
        if !self.title.is_empty() {
            let _ = writeln!(
                s,
                "<text x=\"{}\" y=\"18\" font-size=\"13\" font-weight=\"bold\" fill=\"{INK}\">{}</text>",
                c(l),
                esc(&self.title)
            );
        }
        if !self.x_label.is_empty() {
            let _ = writeln!(
                s,
                "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"{INK}\">{}</text>",
                c(0.5 * (l + r)),
                c(self.h - 8.0),
                esc(&self.x_label)
            );
        }
        if !self.y_label.is_empty() {
            let _ = writeln!(
                s,
                "<text transform=\"translate(14 {}) rotate(-90)\" text-anchor=\"middle\" fill=\"{INK}\">{}</text>",
                c(0.5 * (t + b)),
                esc(&self.y_label)
            );
        }
        // The legend: a box in the plot's top right corner.
        if !self.legend.is_empty() {
            let width = self
                .legend
                .iter()
                .map(|(label, _, _)| label.chars().count())
                .max()
                .unwrap_or(0) as f64
                * 6.3
                + 34.0;
            let height = 8.0 + 16.0 * self.legend.len() as f64;
            // The corner whose box hides the least of what is drawn (top right first).
            let corners = [
                (r - width - 6.0, t + 6.0),
                (l + 6.0, t + 6.0),
                (r - width - 6.0, b - height - 6.0),
                (l + 6.0, b - height - 6.0),
            ];
            let hidden = |(x0, y0): (f64, f64)| {
                self.ink
                    .iter()
                    .filter(|(x, y)| *x >= x0 && *x <= x0 + width && *y >= y0 && *y <= y0 + height)
                    .count()
            };
            let (x0, y0) = corners
                .iter()
                .copied()
                .min_by_key(|c| hidden(*c))
                .unwrap_or(corners[0]);
            let _ = writeln!(
                s,
                "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\" fill-opacity=\"0.85\" stroke=\"#cccccc\"/>",
                c(x0),
                c(y0),
                c(width),
                c(height)
            );
            for (k, (label, color, key)) in self.legend.iter().enumerate() {
                let y = y0 + 14.0 + 16.0 * k as f64;
                let mark = match key {
                    Key::Line => format!("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{color}\" stroke-width=\"2\"/>", c(x0 + 6.0), c(x0 + 24.0), c(y - 4.0)),
                    Key::Dashed => format!("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{color}\" stroke-width=\"2\" stroke-dasharray=\"4 3\"/>", c(x0 + 6.0), c(x0 + 24.0), c(y - 4.0)),
                    Key::Area => format!("<rect x=\"{}\" y=\"{}\" width=\"18\" height=\"9\" fill=\"{color}\" fill-opacity=\"0.35\"/>", c(x0 + 6.0), c(y - 9.0)),
                    Key::Dot => format!("<circle cx=\"{}\" cy=\"{}\" r=\"3.5\" fill=\"{color}\"/>", c(x0 + 15.0), c(y - 4.0)),
                };
                let _ = writeln!(
                    s,
                    "{mark}<text x=\"{}\" y=\"{}\" font-size=\"11\" fill=\"{INK}\">{}</text>",
                    c(x0 + 30.0),
                    c(y),
                    esc(label)
                );
            }
        }
        s.push_str("</svg>\n");
        s
    }
}

/// Ticks of a logarithmic axis: 1, 2, 5 × 10ᵏ within [lo, hi] (just the powers of ten when
/// the range spans more than three decades).
fn log_ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    let mut out = vec![];
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mults: &[f64] = if k1 - k0 > 3 {
        &[1.0]
    } else {
        &[1.0, 2.0, 5.0]
    };
    for k in k0..=k1 {
        for m in mults {
            let v = m * 10f64.powi(k);
            if v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9) {
                out.push((v, fmt_tick(v, if k >= 0 { 1.0 } else { 10f64.powi(k) })));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_fall_on_round_numbers_inside_the_range() {
        let (t, step) = ticks(0.0, 1000.0, 5);
        assert_eq!(step, 200.0);
        assert_eq!(t, vec![0.0, 200.0, 400.0, 600.0, 800.0, 1000.0]);
        let (t, step) = ticks(-0.13, 0.41, 5);
        assert_eq!(step, 0.2);
        assert_eq!(t.len(), 3);
        assert!((t[0] - 0.0).abs() < 1e-12 && (t[2] - 0.4).abs() < 1e-12);
        assert_eq!(fmt_tick(0.4, 0.2), "0.4");
        assert_eq!(fmt_tick(2.5, 2.5), "2.5");
        assert_eq!(fmt_tick(-1500.0, 500.0), "−1500");
        assert_eq!(fmt_tick(20000.0, 5000.0), "20\u{2009}000");
    }

    #[test]
    fn a_map_keeps_one_scale_for_east_and_north() {
        let ch = Chart::map("m", 600.0, 400.0, (-100.0, 300.0), (0.0, 100.0));
        assert!((ch.x.per_unit() - ch.y.per_unit()).abs() < 1e-12);
        // Both ranges are held.
        assert!(ch.x.lo <= -100.0 && ch.x.hi >= 300.0 && ch.y.lo <= 0.0 && ch.y.hi >= 100.0);
    }

    #[test]
    fn text_is_escaped_for_xml() {
        assert_eq!(esc("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
