//! Elementary functions written once over [`Real`], branch-free, so that four lanes run in
//! vector registers and every lane is bit for bit the one-lane result: `atan2` for the
//! angle of attack (the 6-DOF kernel) and `ln`/`exp` for the step-size controller (the
//! batch judges four attempts at once). The system's libm has no four-lane form, and calling
//! it lane by lane would make the batch's lanes differ from single flights wherever libm and
//! a vector version round differently; here both drivers call the same code.

use super::Real;

/// `atan2(y, x)` for `y ≥ 0` (an angle in [0, π]) on lanes, branch-free so that four lanes
/// run in vector registers: Cephes' `atan` (three-interval reduction, degree 4/5 rational
/// core, Moshier 1984–2000) on `y/|x|`, reflected for `x < 0`. Within 1 ulp of the
/// correctly rounded value (the test measures it against the system's `atan2`). Both drivers
/// call it, so the batch's lanes stay bit for bit the single flight.
// The coefficients are Cephes' as published (more digits than a double holds, rounded once).
#[allow(clippy::excessive_precision)]
#[inline(always)]
pub fn atan2_upper<S: Real>(y: S, x: S) -> S {
    const P: [f64; 5] = [
        -8.750608600031904122785e-1,
        -1.615753718733365076637e1,
        -7.500855792314704667340e1,
        -1.228866684490136173410e2,
        -6.485021904942025371773e1,
    ];
    const Q: [f64; 5] = [
        2.485846490142306297962e1,
        1.650270098316988542046e2,
        4.328810604912902668951e2,
        4.853903996359136964868e2,
        1.945506571482613964425e2,
    ];
    // π/2 = FRAC_PI_2 + MOREBITS (the double's shortfall), tan(3π/8), and π's shortfall.
    const MOREBITS: f64 = 6.123233995736765886130e-17;
    const T3P8: f64 = 2.414_213_562_373_095;
    const PI_LO: f64 = 1.224_646_799_147_353_2e-16;
    let zero = S::splat(0.0);
    let one = S::splat(1.0);
    let r = y / x.abs();
    // Reduce r ≥ 0 to |t| ≤ 0.66.
    let big = r.gt(S::splat(T3P8));
    let mid = S::or(big, r.gt(S::splat(0.66)));
    let t_big = -(one / r);
    let t_mid = (r - one) / (r + one);
    let t = S::select(big, t_big, S::select(mid, t_mid, r));
    let base = S::select(
        big,
        S::splat(std::f64::consts::FRAC_PI_2),
        S::select(mid, S::splat(std::f64::consts::FRAC_PI_4), zero),
    );
    let extra = S::select(
        big,
        S::splat(MOREBITS),
        S::select(mid, S::splat(0.5 * MOREBITS), zero),
    );
    let z = t * t;
    let p = (((S::splat(P[0]) * z + S::splat(P[1])) * z + S::splat(P[2])) * z + S::splat(P[3])) * z
        + S::splat(P[4]);
    let q = ((((z + S::splat(Q[0])) * z + S::splat(Q[1])) * z + S::splat(Q[2])) * z
        + S::splat(Q[3]))
        * z
        + S::splat(Q[4]);
    let a = base + ((t * (z * p / q) + extra) + t);
    // y/|x| is +∞ when x = 0 (a = π/2); x < 0 reflects: π − a.
    let reflected = (S::splat(std::f64::consts::PI) - a) + S::splat(PI_LO);
    S::select(zero.gt(x), reflected, a)
}

/// `ln 2` split in two: a high part with trailing zero bits (so `k · LN2_HI` is exact for the
/// exponents a double has) and the rest.
#[allow(clippy::excessive_precision)]
const LN2_HI: f64 = 6.931_471_803_691_238_164_90e-1;
#[allow(clippy::excessive_precision)]
const LN2_LO: f64 = 1.908_214_929_270_587_700_02e-10;
/// `1.5 · 2⁵²`: adding it rounds a double of magnitude below 2⁵¹ to an integer, and the sum's
/// low bits are that integer (two's complement), which is how integers cross between the
/// lanes' floating-point and bit forms here without a conversion instruction.
const MAGIC: f64 = 6_755_399_441_055_744.0;

/// The natural logarithm on lanes: fdlibm's `log` (Sun Microsystems, 1993, as musl keeps it):
/// `x = 2^k (1 + f)` with `1 + f` in [√2/2, √2), then `ln(1 + f)` from `s = f/(2 + f)` and a
/// degree-14 polynomial in `s`. Within 1 ulp of the correctly rounded value (the test measures
/// it against the system's `ln`). `ln 0 = −∞`, `ln ∞ = ∞`, NaN for negative numbers and NaN.
// The coefficients are fdlibm's as published.
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
#[inline(always)]
pub fn ln<S: Real>(x: S) -> S {
    const LG: [f64; 7] = [
        6.666666666666735130e-01,
        3.999999999940941908e-01,
        2.857142874366239149e-01,
        2.222219843214978396e-01,
        1.818357216161805012e-01,
        1.531383769920937332e-01,
        1.479819860511658591e-01,
    ];
    // The high word's shift that puts 1 + f in [√2/2, √2).
    const SHIFT: u64 = 0x3ff0_0000 - 0x3fe6_a09e;
    let zero = S::splat(0.0);
    let one = S::splat(1.0);
    // Subnormal numbers are scaled into the normal range first (their k is 54 less).
    let tiny = S::splat(f64::MIN_POSITIVE).gt(x);
    let xs = S::select(tiny, x * S::splat(18_014_398_509_481_984.0), x);
    let k_tiny = S::select(tiny, S::splat(54.0), zero);
    let m = xs.map(|_, v| {
        let b = v.to_bits();
        let hx = (b >> 32).wrapping_add(SHIFT);
        f64::from_bits((((hx & 0x000f_ffff) + 0x3fe6_a09e) << 32) | (b & 0xffff_ffff))
    });
    let k = xs.map(|_, v| {
        let hx = (v.to_bits() >> 32).wrapping_add(SHIFT);
        let k = (hx >> 20) as i64 - 0x3ff;
        f64::from_bits((MAGIC.to_bits() as i64 + k) as u64)
    }) - S::splat(MAGIC)
        - k_tiny;
    let f = m - one;
    let hfsq = S::splat(0.5) * f * f;
    let s = f / (S::splat(2.0) + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (S::splat(LG[1]) + w * (S::splat(LG[3]) + w * S::splat(LG[5])));
    let t2 =
        z * (S::splat(LG[0]) + w * (S::splat(LG[2]) + w * (S::splat(LG[4]) + w * S::splat(LG[6]))));
    let r = t2 + t1;
    let y = s * (hfsq + r) + k * S::splat(LN2_LO) - hfsq + f + k * S::splat(LN2_HI);
    let y = S::select(x.eq(S::splat(f64::INFINITY)), x, y);
    let y = S::select(x.eq(zero), S::splat(f64::NEG_INFINITY), y);
    S::select(S::or(zero.gt(x), x.ne(x)), S::splat(f64::NAN), y)
}

/// `eˣ` on lanes: fdlibm's `exp` (Sun Microsystems, 1993): `x = k ln 2 + r` with
/// `|r| ≤ ln 2 / 2`, `eʳ` from a degree-10 rational form, scaled by `2^k` (in two factors,
/// so that neither leaves the normal range). Within 1 ulp of the correctly rounded value
/// (the test measures it against the system's `exp`). 0 below −746, ∞ above 710, NaN for NaN.
// The coefficients are fdlibm's as published.
#[allow(clippy::excessive_precision)]
#[inline(always)]
pub fn exp<S: Real>(x: S) -> S {
    // fdlibm's `invln2`, 1/ln 2 = log₂ e (the same double as the standard library's).
    const INVLN2: f64 = std::f64::consts::LOG2_E;
    const P: [f64; 5] = [
        1.666_666_666_666_660_190_37e-1,
        -2.777_777_777_701_559_338_42e-3,
        6.613_756_321_437_934_361_17e-5,
        -1.653_390_220_546_525_153_90e-6,
        4.138_136_797_057_238_460_39e-8,
    ];
    let one = S::splat(1.0);
    let magic = S::splat(MAGIC);
    // Held in [−746, 710], where the result is 0 and ∞ at the ends (NaN, which `max` drops,
    // is put back at the end).
    let xc = -((-x.max(S::splat(-746.0))).max(S::splat(-710.0)));
    let k = (xc * S::splat(INVLN2) + magic) - magic;
    let hi = xc - k * S::splat(LN2_HI);
    let lo = k * S::splat(LN2_LO);
    let r = hi - lo;
    let rr = r * r;
    let c = r - rr
        * (S::splat(P[0])
            + rr * (S::splat(P[1])
                + rr * (S::splat(P[2]) + rr * (S::splat(P[3]) + rr * S::splat(P[4])))));
    let y = one - ((lo - (r * c) / (S::splat(2.0) - c)) - hi);
    // 2^k as 2^k1 · 2^k2, each factor normal (|k1|, |k2| ≤ 538), built from its bits.
    let k1 = (k * S::splat(0.5) + magic) - magic;
    let k2 = k - k1;
    let pow2 = |k: S| {
        (k + magic).map(|_, v| {
            let k = v.to_bits().wrapping_sub(MAGIC.to_bits());
            f64::from_bits(k.wrapping_add(1023) << 52)
        })
    };
    let e = y * pow2(k1) * pow2(k2);
    S::select(x.ne(x), x, e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::tests::uniform;
    use crate::lanes::F64x4;

    /// Distance in units in the last place between two doubles of the same sign.
    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64)
            .wrapping_sub(b.to_bits() as i64)
            .unsigned_abs()
    }

    /// The largest distance, in ulps, of `one` from the system's `sys` over `xs`, each four
    /// of `xs` also taken through `four` and checked bit for bit against `one` lane by lane
    /// (a last short four padded with 1).
    fn worst_ulps(
        xs: &[f64],
        four: impl Fn(F64x4) -> F64x4,
        one: impl Fn(f64) -> f64,
        sys: impl Fn(f64) -> f64,
    ) -> u64 {
        let mut worst = 0;
        for w in xs.chunks(4) {
            let mut x4 = [1.0; 4];
            x4[..w.len()].copy_from_slice(w);
            let lanes = four(F64x4(x4));
            for (i, &x) in x4.iter().enumerate() {
                let ours = one(x);
                worst = worst.max(ulps(ours, sys(x)));
                assert_eq!(lanes.0[i].to_bits(), ours.to_bits(), "at {x}: lane {i}");
            }
        }
        worst
    }

    #[test]
    fn the_lane_atan2_is_within_one_ulp_of_the_system_s() {
        // Angles of attack from 1e-12 rad to π, both signs of x, ratios across 30 decades.
        let mut worst = 0;
        let mut next = uniform(0x1234_5678_9abc_def0);
        for i in 0..400_000 {
            let y = 10f64.powf(-8.0 + 12.0 * next());
            let mag = 10f64.powf(-10.0 + 18.0 * next());
            let x = if i % 2 == 0 { mag } else { -mag };
            let (ours, sys) = (atan2_upper(y, x), y.atan2(x));
            worst = worst.max(ulps(ours, sys));
            let four = atan2_upper(F64x4([y, y, y, y]), F64x4([x, -x, mag, 0.0]));
            assert_eq!(four.0[0].to_bits(), ours.to_bits());
            assert_eq!(four.0[1].to_bits(), atan2_upper(y, -x).to_bits());
        }
        assert_eq!(atan2_upper(1.0, 0.0), std::f64::consts::FRAC_PI_2);
        assert_eq!(atan2_upper(0.0, 1.0), 0.0);
        assert_eq!(atan2_upper(0.0, -1.0), std::f64::consts::PI);
        eprintln!("worst difference from the system's atan2: {worst} ulp");
        assert!(worst <= 1, "{worst} ulp (bound 1)");
    }

    #[test]
    fn the_lane_logarithm_is_within_one_ulp_of_the_system_s() {
        let mut next = uniform(0x2545_f491_4f6c_dd1d);
        let mut xs: Vec<f64> = (0..400_000)
            .map(|_| 10f64.powf(-320.0 + 628.0 * next()))
            .collect();
        // Near 1, where ln is smallest and most easily spoiled, and the step controller's
        // error norms (1e-6 to 1e3).
        xs.extend((0..100_000).map(|_| 1.0 + (next() - 0.5) * 1e-3));
        xs.extend((0..100_000).map(|_| 10f64.powf(-6.0 + 9.0 * next())));
        xs.extend([
            1.0,
            2.0,
            0.5,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            std::f64::consts::E,
        ]);
        let worst = worst_ulps(&xs, ln, ln, f64::ln);
        assert_eq!(ln(1.0), 0.0);
        assert_eq!(ln(0.0), f64::NEG_INFINITY);
        assert_eq!(ln(-0.0), f64::NEG_INFINITY);
        assert_eq!(ln(f64::INFINITY), f64::INFINITY);
        assert!(ln(-1.0).is_nan() && ln(f64::NAN).is_nan() && ln(f64::NEG_INFINITY).is_nan());
        eprintln!("worst difference from the system's ln: {worst} ulp");
        assert!(worst <= 1, "{worst} ulp (bound 1)");
    }

    #[test]
    fn the_lane_exponential_is_within_one_ulp_of_the_system_s() {
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let mut xs: Vec<f64> = (0..400_000).map(|_| -745.0 + 1454.0 * next()).collect();
        xs.extend((0..100_000).map(|_| (next() - 0.5) * 1e-6));
        xs.extend((0..100_000).map(|_| (next() - 0.5) * 20.0));
        xs.extend([0.0, -0.0, 1.0, -1.0, 709.78, -708.0, -744.0, 1e-300]);
        let worst = worst_ulps(&xs, exp, exp, f64::exp);
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(710.0), f64::INFINITY);
        assert_eq!(exp(1e300), f64::INFINITY);
        assert_eq!(exp(f64::INFINITY), f64::INFINITY);
        assert_eq!(exp(-746.0), 0.0);
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert!(exp(f64::NAN).is_nan());
        eprintln!("worst difference from the system's exp: {worst} ulp");
        assert!(worst <= 1, "{worst} ulp (bound 1)");
    }
}
