//! The core's f32 sine and cosine against f64 references.

use skyroute::geometry::trig::sin_cos;

#[test]
fn sin_cos_within_1_5e7_of_f64() {
    let mut worst = 0.0f64;
    let mut x = -12_000.0f64;
    let mut checked = 0u64;
    let mut worst_at = 0.0;
    // Dense near zero and the quadrant boundaries, coarse far out.
    while x <= 12_000.0 {
        let xf = x as f32;
        let (s, c) = sin_cos(xf);
        let (rs, rc) = (xf as f64).sin_cos();
        let e = (s as f64 - rs).abs().max((c as f64 - rc).abs());
        if e > worst {
            worst = e;
            worst_at = x;
        }
        checked += 1;
        x += if x.abs() < 20.0 { 1.3e-4 } else { 0.37 };
    }
    for k in -2000..2000 {
        for d in [-1e-6f64, 0.0, 1e-6] {
            let xf = (k as f64 * std::f64::consts::FRAC_PI_4 + d) as f32;
            let (s, c) = sin_cos(xf);
            let (rs, rc) = (xf as f64).sin_cos();
            worst = worst.max((s as f64 - rs).abs()).max((c as f64 - rc).abs());
            checked += 1;
        }
    }
    println!("sin_cos: {checked} arguments, worst absolute error {worst:.3e} (sweep worst at {worst_at})");
    assert!(worst < 1.5e-7, "worst error {worst:e}");
    assert!(sin_cos(f32::NAN).0.is_nan());
    assert!(sin_cos(f32::INFINITY).1.is_nan());
}
