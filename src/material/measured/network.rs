//! The Neural-BRDF network (Sztrajman, Rainer, Ritschel, Weyrich, "Neural
//! BRDF Representation and Importance Sampling", CGF 40(6), 2021): a
//! 6-21-21-3 multilayer perceptron from the half/difference vectors to RGB
//! `f_r` in 1/sr, evaluated in `f64` as its weights file defines it
//! (`data/measured/merl100_nbrdf_weights.json`, keys `forward`, `layout`):
//!
//! `a1 = relu(x·W1 + b1)`, `a2 = relu(a1·W2 + b2)`, `y = exp(a2·W3 + b3) − 1`,
//! `f_r = max(0, y)`, with `W[in][out]` (Keras' layout) and
//! `x = (h_x, h_y, h_z, d_x, d_y, d_z)` ([`super::coords::HalfDiff`]).

use crate::base::Rgb;

/// Inputs, hidden units per layer, outputs.
pub const INPUTS: usize = 6;
pub const HIDDEN: usize = 21;
pub const OUTPUTS: usize = 3;
/// Weights and biases in all: 6·21 + 21 + 21·21 + 21 + 21·3 + 3.
pub const WEIGHT_COUNT: usize = 675;

/// One material's network.
#[derive(Clone, Debug, PartialEq)]
pub struct Network {
    pub w1: [[f64; HIDDEN]; INPUTS],
    pub b1: [f64; HIDDEN],
    pub w2: [[f64; HIDDEN]; HIDDEN],
    pub b2: [f64; HIDDEN],
    pub w3: [[f64; OUTPUTS]; HIDDEN],
    pub b3: [f64; OUTPUTS],
}

impl Network {
    /// The network's output `y` (before the clamp) for input `x`.
    pub fn forward(&self, x: [f64; INPUTS]) -> [f64; OUTPUTS] {
        let a1 = dense_relu(&x, &self.w1, &self.b1);
        let a2 = dense_relu(&a1, &self.w2, &self.b2);
        let mut y = self.b3;
        for (a, row) in a2.iter().zip(&self.w3) {
            for (yc, w) in y.iter_mut().zip(row) {
                *yc += a * w;
            }
        }
        y.map(|z| z.exp() - 1.0)
    }

    /// `f_r = max(0, y)` [1/sr] at the half/difference vectors `h`, `d`.
    pub fn f_r(&self, h: glam::DVec3, d: glam::DVec3) -> Rgb {
        let y = self.forward([h.x, h.y, h.z, d.x, d.y, d.z]);
        Rgb::from_array(y).max(Rgb::ZERO)
    }

    /// The weights in the order the GPU reads them: W1 row by row, b1, W2,
    /// b2, W3, b3 ([`WEIGHT_COUNT`] numbers).
    pub fn flat(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(WEIGHT_COUNT);
        self.w1.iter().for_each(|r| out.extend(r));
        out.extend(self.b1);
        self.w2.iter().for_each(|r| out.extend(r));
        out.extend(self.b2);
        self.w3.iter().for_each(|r| out.extend(r));
        out.extend(self.b3);
        out
    }
}

/// `relu(x·W + b)` with `W[in][out]`.
fn dense_relu<const I: usize>(
    x: &[f64; I],
    w: &[[f64; HIDDEN]; I],
    b: &[f64; HIDDEN],
) -> [f64; HIDDEN] {
    let mut z = *b;
    for (xi, row) in x.iter().zip(w) {
        for (zj, wij) in z.iter_mut().zip(row) {
            *zj += xi * wij;
        }
    }
    z.map(|v| v.max(0.0))
}
