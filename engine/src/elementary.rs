//! Elementary functions for the hot loops: ln x, e^y and x^w, inlined and
//! without a division.
//!
//! The library's `ln`, `exp` and `powf` are calls that the compiler can neither
//! inline nor schedule around; in the seed 001 experiment `powf` (the weighted
//! rule's power transform) was a fifth of the time, and `ln` (the Gamma
//! sampler's rejection test) a few per cent more. The kernels here reduce the
//! argument with a table of 64 entries, so that a polynomial of degree 5 (e^r)
//! or 7 (ln(1 + r)) is exact to rounding, and need no division: each costs a
//! few nanoseconds and runs in parallel with its neighbours. Their tables are
//! computed at compile time by fdlibm's kernels (Sun Microsystems, `e_log.c`
//! and `e_exp.c`, freely distributable, each accurate to within an ulp), and
//! every operation is an IEEE addition, multiplication or conversion, never a
//! fused multiply-add, so a result is the same on every machine and build.
//! Each function states its domain; inputs outside it go to the library.
//!
//! Accuracy (tested against the library): ln within 2⁻⁵² absolute plus two
//! ulps, e^y within three ulps; x^w as exp(w · ln x) carries the rounding of
//! ln x into the exponent, a relative error of about |w ln x| · 2⁻⁵² on top
//! (10⁻¹⁴ at most for w ≤ 1 and x ≥ 10⁻⁹, the power transform's inputs).

/// ln 2, split so that k · [`LN2_HI`] is exact for |k| < 2²¹.
const LN2_HI: f64 = 6.931_471_803_691_238e-1;
/// ln 2 − [`LN2_HI`].
const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
/// Table entries: the argument's reduction step is 1/64 (ln) or ln 2 / 64 (exp).
const STEPS: usize = 64;
const MANTISSA: u64 = (1 << 52) - 1;

/// x^w, as exp(w · ln x) for a positive normal x and a result between e⁻⁷⁰⁸
/// and e⁷⁰⁹, by `powf` otherwise.
#[inline]
pub(crate) fn pow(x: f64, w: f64) -> f64 {
    let (power, exact) = pow_kernel(x, w);
    if exact { power } else { x.powf(w) }
}

/// `powers[i] = xs[i]^ws[i]`, the same values as [`pow`] one by one: the
/// kernels run over the slice four at a time without a branch (so that the
/// compiler vectorises them), and only the rare inputs outside their domain
/// go to `powf` afterwards.
///
/// Compiled twice and chosen at run time: for the baseline x86-64 (two lanes
/// a register) and for AVX2 (four), by `multiversion`. The two give the same
/// bits: the kernels are IEEE additions, multiplications and conversions,
/// which AVX2 computes as SSE2 does, and FMA, which could fuse them, is not
/// enabled (nor would the compiler fuse them without being asked).
#[multiversion::multiversion(targets("x86_64+avx2"))]
pub(crate) fn pow_many(xs: &[f64], ws: &[f64], powers: &mut [f64]) {
    pow_lanes(xs, ws, powers);
}

/// [`pow_many`]'s body, inlined into each of its versions.
#[inline(always)]
fn pow_lanes(xs: &[f64], ws: &[f64], powers: &mut [f64]) {
    const LANES: usize = 4;
    debug_assert!(xs.len() == ws.len() && xs.len() == powers.len());
    let whole = xs.len() / LANES * LANES;
    let mut all_exact = true;
    for ((power, x), w) in powers[..whole]
        .chunks_exact_mut(LANES)
        .zip(xs.chunks_exact(LANES))
        .zip(ws.chunks_exact(LANES))
    {
        // Lane by lane in separate loops, as the compiler vectorises them.
        let mut y = [0.0; LANES];
        let mut exact = [false; LANES];
        for lane in 0..LANES {
            y[lane] = w[lane] * ln_normal(x[lane]);
            exact[lane] = in_domain(x[lane], y[lane]);
        }
        for lane in 0..LANES {
            // NaN marks the inputs left to the library: the kernel never returns it.
            let value = exp_normal(if exact[lane] { y[lane] } else { 0.0 });
            power[lane] = if exact[lane] { value } else { f64::NAN };
            all_exact &= exact[lane];
        }
    }
    for ((power, &x), &w) in powers[whole..].iter_mut().zip(&xs[whole..]).zip(&ws[whole..]) {
        let (value, exact) = pow_kernel(x, w);
        all_exact &= exact;
        *power = if exact { value } else { f64::NAN };
    }
    if !all_exact {
        for ((power, &x), &w) in powers.iter_mut().zip(xs).zip(ws) {
            if power.is_nan() {
                *power = x.powf(w);
            }
        }
    }
}

/// Whether the kernels give x^w for y = w ln x (computed by [`ln_normal`]):
/// x positive and normal, y in [−708, 709] (a normal result).
#[inline]
fn in_domain(x: f64, y: f64) -> bool {
    is_positive_normal(x) & (-708.0..=709.0).contains(&y)
}

/// x^w by the kernels, and whether they apply: x positive and normal, w ln x
/// in [−708, 709] (a normal result). Branch-free.
#[inline]
fn pow_kernel(x: f64, w: f64) -> (f64, bool) {
    let y = w * ln_normal(x);
    let exact = in_domain(x, y);
    // Outside the domain, exp's kernel still runs on a harmless argument.
    (exp_normal(if exact { y } else { 0.0 }), exact)
}

/// ln x: the kernel below for a positive normal x, the library otherwise.
#[inline]
pub(crate) fn ln(x: f64) -> f64 {
    if is_positive_normal(x) { ln_normal(x) } else { x.ln() }
}

/// Whether x is positive, finite and not subnormal.
#[inline]
fn is_positive_normal(x: f64) -> bool {
    (f64::MIN_POSITIVE..=f64::MAX).contains(&x)
}

/// 1/cⱼ for cⱼ = 1 + j/64, j = 0..=64: the centres of the mantissa's
/// intervals, the first exactly 1 so that ln 1 = 0 exactly.
const INVERSE_CENTRES: [f64; STEPS + 1] = {
    let mut table = [0.0; STEPS + 1];
    let mut j = 0;
    while j <= STEPS {
        table[j] = 1.0 / (1.0 + j as f64 / STEPS as f64);
        j += 1;
    }
    table
};

/// −ln of each entry of [`INVERSE_CENTRES`] (as rounded), so that
/// ln m = ln(m / cⱼ) − ln(1/cⱼ) holds for the stored 1/cⱼ.
const LN_CENTRES: [f64; STEPS + 1] = {
    let mut table = [0.0; STEPS + 1];
    let mut j = 0;
    while j <= STEPS {
        table[j] = -fdlibm_ln(INVERSE_CENTRES[j]);
        j += 1;
    }
    table
};

/// 2^(j/64).
const POWERS_OF_TWO: [f64; STEPS] = {
    let mut table = [0.0; STEPS];
    let mut j = 0;
    while j < STEPS {
        table[j] = fdlibm_exp(j as f64 * (std::f64::consts::LN_2 / STEPS as f64));
        j += 1;
    }
    table
};

/// ln x for a positive normal x: x = 2^k · m with m in [1, 2), cⱼ the
/// centre nearest m, ln x = k ln 2 + ln cⱼ + ln(1 + r) with r = m/cⱼ − 1,
/// |r| ≤ 1/128, where ln(1 + r)'s series to r⁷ is exact to 2·10⁻¹⁸.
#[inline]
fn ln_normal(x: f64) -> f64 {
    let bits = x.to_bits();
    let k = f64::from((bits >> 52) as i32 - 1023);
    // The mantissa's top 7 bits, rounded to 6: the nearest centre.
    let j = ((((bits & MANTISSA) >> (51 - STEPS.trailing_zeros())) + 1) >> 1) as usize;
    let m = f64::from_bits((bits & MANTISSA) | (1023 << 52));
    // j ≤ 64 always; the `min` spares a bounds check, which would keep the
    // compiler from vectorising `pow_many`.
    let j = j.min(STEPS);
    let r = m * INVERSE_CENTRES[j] - 1.0;
    let r2 = r * r;
    // r − r²/2 + r³/3 − … + r⁷/7, in pairs (Estrin) to shorten the chain.
    let series = r + r2 * ((-0.5 + r * (1.0 / 3.0)) + r2 * ((-0.25 + r * 0.2) + r2 * (-1.0 / 6.0 + r * (1.0 / 7.0))));
    k * LN2_HI + (LN_CENTRES[j] + (series + k * LN2_LO))
}

/// e^y for y in [−708, 709], whose result is normal: y = (64n + j) ln 2 / 64 +
/// r with |r| ≤ ln 2 / 128, e^y = 2ⁿ · 2^(j/64) · e^r, where e^r's series to
/// r⁵ is exact to 4·10⁻¹⁷.
#[inline]
fn exp_normal(y: f64) -> f64 {
    const INVERSE_STEP: f64 = STEPS as f64 / std::f64::consts::LN_2;
    // k = y · 64 / ln 2 rounded half away from zero.
    let (kf, k) = truncated(y * INVERSE_STEP + if y < 0.0 { -0.5 } else { 0.5 });
    // |k| < 2¹⁷, so k · LN2_HI / 64 is exact.
    let r = (y - kf * (LN2_HI / STEPS as f64)) - kf * (LN2_LO / STEPS as f64);
    let r2 = r * r;
    let series = 1.0 + (r + r2 * ((0.5 + r * (1.0 / 6.0)) + r2 * ((1.0 / 24.0) + r * (1.0 / 120.0))));
    let n = k >> STEPS.trailing_zeros();
    let j = (k & (STEPS as i32 - 1)) as usize % STEPS;
    // 2ⁿ is normal for n in [−1022, 1023], which y's range keeps.
    POWERS_OF_TWO[j] * series * f64::from_bits(u64::from((n + 1023) as u32) << 52)
}

/// t truncated toward zero, as a float (+0 for zero) and as an integer, for
/// |t| < 2³¹: what `f64::from(t as i32)` and `t as i32` give, without a branch
/// (`f64::trunc` is a library call on x86-64 without SSE4.1, and `as`, which
/// saturates, is compiled lane by lane). Adding 1.5 · 2⁵² rounds t to the
/// nearest integer; the truncation steps back toward zero where that went
/// away from it; that integer plus 1.5 · 2⁵² holds it in its low bits.
#[inline]
fn truncated(t: f64) -> (f64, i32) {
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let nearest = (t + ROUND) - ROUND;
    let whole = nearest - if (nearest > t) & (t >= 0.0) { 1.0 } else { 0.0 }
        + if (nearest < t) & (t < 0.0) { 1.0 } else { 0.0 };
    (whole, (whole + ROUND).to_bits() as i32)
}

/// fdlibm's `__ieee754_log` for a positive normal x, within an ulp: builds
/// [`LN_CENTRES`] at compile time.
const fn fdlibm_ln(x: f64) -> f64 {
    const LG1: f64 = 6.666_666_666_666_735e-1;
    const LG2: f64 = 3.999_999_999_940_942e-1;
    const LG3: f64 = 2.857_142_874_366_239e-1;
    const LG4: f64 = 2.222_219_843_214_978_4e-1;
    const LG5: f64 = 1.818_357_216_161_805e-1;
    const LG6: f64 = 1.531_383_769_920_937_3e-1;
    const LG7: f64 = 1.479_819_860_511_658_6e-1;
    let bits = x.to_bits();
    // x = 2^k · m with m in [√2/2, √2) (fdlibm's test on the top bits).
    let high = (bits & MANTISSA) >> 32;
    let halve = (high + 0x9_5f64 > 0xf_ffff) as u64;
    let k = ((bits >> 52) as i64 - 1023 + halve as i64) as f64;
    let m = f64::from_bits((bits & MANTISSA) | ((1023 - halve) << 52));
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (LG2 + w * (LG4 + w * LG6));
    let t2 = z * (LG1 + w * (LG3 + w * (LG5 + w * LG7)));
    let r = t2 + t1;
    let hfsq = 0.5 * f * f;
    k * LN2_HI - ((hfsq - (s * (hfsq + r) + k * LN2_LO)) - f)
}

/// fdlibm's `__ieee754_exp` for y in [0, ln 2], within an ulp: builds
/// [`POWERS_OF_TWO`] at compile time.
const fn fdlibm_exp(y: f64) -> f64 {
    const P1: f64 = 1.666_666_666_666_660_2e-1;
    const P2: f64 = -2.777_777_777_701_559_3e-3;
    const P3: f64 = 6.613_756_321_437_934e-5;
    const P4: f64 = -1.653_390_220_546_525_2e-6;
    const P5: f64 = 4.138_136_797_057_238_5e-8;
    // y = k ln 2 + r with |r| ≤ ln 2 / 2, k in {0, 1}.
    let k = if y > 0.5 * std::f64::consts::LN_2 { 1.0 } else { 0.0 };
    let hi = y - k * LN2_HI;
    let lo = k * LN2_LO;
    let r = hi - lo;
    let t = r * r;
    let c = r - t * (P1 + t * (P2 + t * (P3 + t * (P4 + t * P5))));
    let e = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi);
    if k > 0.0 { 2.0 * e } else { e }
}

#[cfg(test)]
mod tests {
    use proptest::collection::vec;
    use proptest::prelude::*;
    use proptest::test_runner::TestRunner;

    use super::*;

    /// 20 000 cases from a fixed seed, whatever the `PROPTEST_*` variables say
    /// (`crate::pinned`).
    fn runner() -> TestRunner {
        crate::pinned::runner(20_000, 0x5167_4711_0020)
    }

    /// Relative difference of a and b.
    fn relative(a: f64, b: f64) -> f64 {
        if a == b {
            0.0
        } else {
            (a - b).abs() / a.abs().max(b.abs())
        }
    }

    /// ln: within 2⁻⁵² absolute plus two ulps of the result.
    #[test]
    fn ln_is_within_rounding_of_the_library() {
        runner()
            .run(&(-1022.0..1023.0_f64, 1.0..2.0_f64), |(exponent, mantissa)| {
                let x = mantissa * 2f64.powi(exponent as i32);
                let (ours, library) = (ln_normal(x), x.ln());
                prop_assert!(
                    (ours - library).abs() <= 2.3e-16 + 4.5e-16 * library.abs(),
                    "ln {x}: {ours} {library}"
                );
                Ok(())
            })
            .unwrap();
        for x in [
            1.0,
            1.0f64.next_up(),
            1.0f64.next_down(),
            2.0,
            0.5,
            f64::MIN_POSITIVE,
            f64::MAX,
        ] {
            assert!((ln(x) - x.ln()).abs() <= 2.3e-16 + 4.5e-16 * x.ln().abs(), "ln {x}");
        }
        assert_eq!(ln(1.0), 0.0);
        for x in [0.0, 1e-310, -1.0, f64::INFINITY, f64::NAN] {
            assert!(ln(x) == x.ln() || ln(x).is_nan() && x.ln().is_nan(), "{x}");
        }
    }

    /// e^y: within three ulps.
    #[test]
    fn exp_is_within_rounding_of_the_library() {
        runner()
            .run(&(-708.0..709.0_f64), |y| {
                prop_assert!(
                    relative(exp_normal(y), y.exp()) <= 6.7e-16,
                    "{y}: {} {}",
                    exp_normal(y),
                    y.exp()
                );
                Ok(())
            })
            .unwrap();
        assert_eq!(exp_normal(0.0), 1.0);
    }

    /// The tables' builders are fdlibm's kernels, within an ulp of the library.
    #[test]
    fn tables_are_within_an_ulp() {
        for (&x, &ln) in INVERSE_CENTRES.iter().zip(&LN_CENTRES) {
            assert!(relative(-ln, x.ln()) <= 2.3e-16, "ln {x}");
        }
        for (j, &power) in POWERS_OF_TWO.iter().enumerate() {
            let y = j as f64 * std::f64::consts::LN_2 / STEPS as f64;
            assert!(relative(power, y.exp()) <= 2.3e-16, "exp {y}");
        }
    }

    /// Over the power transform's inputs (a mass ratio in (0, 1], a weight up
    /// to 16) the result is within three ulps plus the rounding of ln x
    /// scaled by w of `powf` (10⁻¹⁴ for w ≤ 1 and x ≥ 10⁻⁹); outside the
    /// kernels' domain it is `powf`'s.
    #[test]
    fn pow_matches_powf() {
        runner()
            .run(&(-40.0..0.0_f64, 1e-3..16.0_f64), |(log10, w)| {
                let x = 10f64.powf(log10);
                let y = w * x.ln();
                let bound = 6.7e-16 + 2.3e-16 * w * (1.0 + 2.0 * x.ln().abs());
                prop_assert!(relative(pow(x, w), x.powf(w)) <= bound, "{x}^{w}, e^{y}");
                Ok(())
            })
            .unwrap();
        for (x, w) in [
            (0.0, 0.5),
            (1e-310, 0.5),
            (1e-300, 16.0),
            (f64::NAN, 1.0),
            (0.5, f64::NAN),
        ] {
            let (ours, library) = (pow(x, w), x.powf(w));
            assert!(
                ours == library || ours.is_nan() && library.is_nan(),
                "{x}^{w}: {ours} {library}"
            );
        }
        assert_eq!(pow(1.0, 0.3), 1.0);
    }

    /// The version of `pow_many` this processor runs (AVX2 where it has it)
    /// and its body compiled for the baseline (this test's own code) give the
    /// bits of `pow` one by one, over the power transform's inputs: rows of
    /// ratios in (0, 1] and weights up to 16, a few outside the domain.
    #[test]
    fn pow_many_gives_the_same_bits_on_every_processor() {
        let inputs = (vec(-40.0..0.0_f64, 1..40), vec(1e-3..16.0_f64, 40));
        runner()
            .run(&inputs, |(log10s, mut ws)| {
                let mut xs: Vec<f64> = log10s.iter().map(|&l| 10f64.powf(l)).collect();
                ws.truncate(xs.len());
                if xs.len() > 3 {
                    (xs[1], xs[2]) = (0.0, 1e-310);
                }
                let one_by_one: Vec<u64> = xs.iter().zip(&ws).map(|(&x, &w)| pow(x, w).to_bits()).collect();
                let (mut dispatched, mut baseline) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
                pow_many(&xs, &ws, &mut dispatched);
                pow_lanes(&xs, &ws, &mut baseline);
                prop_assert_eq!(
                    dispatched.iter().map(|p| p.to_bits()).collect::<Vec<_>>(),
                    one_by_one.clone()
                );
                prop_assert_eq!(baseline.iter().map(|p| p.to_bits()).collect::<Vec<_>>(), one_by_one);
                Ok(())
            })
            .unwrap();
    }

    /// `truncated` is `as i32` (and back) on integers, halves and their
    /// neighbours, and on 20 000 random values, across exp's range of t.
    #[test]
    fn truncated_is_the_cast() {
        let check = |t: f64| {
            let (whole, k) = truncated(t);
            assert_eq!((whole.to_bits(), k), (f64::from(t as i32).to_bits(), t as i32), "{t}");
        };
        for n in -70_000..=70_000 {
            for t in [f64::from(n), f64::from(n) + 0.5] {
                [t, t.next_up(), t.next_down()].into_iter().for_each(check);
            }
        }
        for t in [0.0, -0.0, 1e-300, -1e-300, 2_147_483_647.0, -2_147_483_648.0] {
            check(t);
        }
        runner()
            .run(&(-70_000.0..70_000.0_f64), |t| {
                check(t);
                Ok(())
            })
            .unwrap();
    }

    /// `pow_many` gives `pow`'s values, inputs outside the kernels' domain among them.
    #[test]
    fn pow_many_is_pow_one_by_one() {
        let xs = [0.5, 0.0, 1e-310, 0.25, 1e-300, 1.0, 0.9, f64::NAN, 3.0];
        let ws = [0.3, 0.5, 0.5, 1.7, 16.0, 0.2, 0.01, 1.0, 2.0];
        let mut powers = [0.0; 9];
        pow_many(&xs, &ws, &mut powers);
        for ((&x, &w), &power) in xs.iter().zip(&ws).zip(&powers) {
            assert!(
                power.to_bits() == pow(x, w).to_bits() || power.is_nan() && x.is_nan(),
                "{x}^{w}"
            );
        }
    }
}
