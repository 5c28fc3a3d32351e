//! The few complex-number operations the Airy summation needs: a film over
//! a conductor has complex indices, amplitudes and phase factors.
//! (`num-complex` is not a dependency; these are six lines each.)

use std::ops::{Add, Div, Mul, Sub};

/// `re + i·im`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Complex {
    pub re: f64,
    pub im: f64,
}

impl Complex {
    pub const ONE: Complex = Complex { re: 1.0, im: 0.0 };

    pub const fn new(re: f64, im: f64) -> Self {
        Complex { re, im }
    }

    /// The real number `x`.
    pub const fn real(x: f64) -> Self {
        Complex { re: x, im: 0.0 }
    }

    /// `e^{iφ}`.
    pub fn cis(phase: f64) -> Self {
        Complex::new(phase.cos(), phase.sin())
    }

    /// `|z|²`.
    pub fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    /// The principal square root (`re ≥ 0`; for `im ≥ 0` also `im ≥ 0`),
    /// taken without cancellation: the larger part is
    /// `√((|z| + |re z|)/2)`, the other follows from `2·re·im = im z`.
    pub fn sqrt(self) -> Self {
        let r = self.norm_sqr().sqrt();
        let big = (0.5 * (r + self.re.abs())).sqrt();
        if big == 0.0 {
            return Complex::real(0.0);
        }
        let small = 0.5 * self.im / big;
        if self.re >= 0.0 {
            Complex::new(big, small)
        } else {
            Complex::new(small.abs(), big.copysign(self.im))
        }
    }
}

impl Add for Complex {
    type Output = Complex;
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
}

impl Sub for Complex {
    type Output = Complex;
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
}

impl Mul for Complex {
    type Output = Complex;
    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}

impl Mul<f64> for Complex {
    type Output = Complex;
    fn mul(self, s: f64) -> Complex {
        Complex::new(self.re * s, self.im * s)
    }
}

impl Div for Complex {
    type Output = Complex;
    fn div(self, o: Complex) -> Complex {
        let d = o.norm_sqr();
        Complex::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sqrt(z)² = z` with `re ≥ 0` in every quadrant, and the branch cut
    /// on the negative real axis gives `+i·√|x|`.
    #[test]
    fn sqrt_squares_back_on_the_principal_branch() {
        for (re, im) in [
            (4.0, 0.0),
            (-4.0, 0.0),
            (0.3, 2.0),
            (-0.3, 2.0),
            (-0.3, -2.0),
            (0.3, -2.0),
            (-1e-9, 5.0),
        ] {
            let z = Complex::new(re, im);
            let s = z.sqrt();
            let back = s * s;
            assert!(s.re >= 0.0, "{z:?} -> {s:?}");
            assert!((back - z).norm_sqr().sqrt() <= 1e-15 * z.norm_sqr().sqrt().max(1.0));
        }
        assert_eq!(Complex::new(-4.0, 0.0).sqrt(), Complex::new(0.0, 2.0));
    }

    /// `z / w · w = z`.
    #[test]
    fn division_inverts_multiplication() {
        let (z, w) = (Complex::new(0.7, -1.3), Complex::new(-2.0, 0.25));
        let back = z / w * w;
        assert!((back - z).norm_sqr().sqrt() < 1e-15);
    }
}
