//! Isotropic hardening laws `σ_y(ε̄ᵖ)`: perfect, linear, piecewise-linear
//! tables (constant past the last point) and Voce's saturating exponential.

/// A yield-stress curve as a function of the equivalent plastic strain.
#[derive(Debug, Clone, PartialEq)]
pub enum Hardening {
    /// Perfect plasticity: `σ_y = σ_y0` (H = 0).
    Perfect {
        /// Initial yield stress (Pa).
        yield_stress: f64,
    },
    /// Linear hardening: `σ_y = σ_y0 + H ε̄ᵖ`.
    Linear {
        /// Initial yield stress (Pa).
        yield_stress: f64,
        /// Plastic hardening modulus H (Pa), ≥ 0.
        modulus: f64,
    },
    /// Piecewise-linear table of `(ε̄ᵖ, σ_y)` points, the first at `ε̄ᵖ = 0`,
    /// strains increasing, stresses non-decreasing; constant past the last point.
    Table {
        /// Equivalent plastic strains (−), starting at 0.
        strains: Vec<f64>,
        /// Yield stresses (Pa) at those strains.
        stresses: Vec<f64>,
    },
    /// Voce: `σ_y = σ_y0 + Q (1 − e^{−b ε̄ᵖ})` (Voce 1948), saturating at
    /// `σ_y0 + Q`.
    Voce {
        /// Initial yield stress σ_y0 (Pa).
        yield_stress: f64,
        /// Saturation stress Q (Pa), ≥ 0.
        saturation: f64,
        /// Saturation rate b (−), > 0.
        rate: f64,
    },
}

impl std::fmt::Display for Hardening {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Perfect { yield_stress } => write!(f, "perfect plasticity, σ_y = {:.4} MPa", yield_stress * 1e-6),
            Self::Linear { yield_stress, modulus } => {
                write!(f, "linear hardening, σ_y0 = {:.4} MPa, H = {:.4} MPa", yield_stress * 1e-6, modulus * 1e-6)
            }
            Self::Voce { yield_stress, saturation, rate } => write!(
                f,
                "Voce hardening, σ_y0 = {:.4} MPa, Q = {:.4} MPa, b = {rate}",
                yield_stress * 1e-6,
                saturation * 1e-6
            ),
            Self::Table { strains, stresses } => write!(
                f,
                "tabulated hardening, {} points, σ_y from {:.4} MPa (peeq 0) to {:.4} MPa (peeq {})",
                strains.len(),
                stresses[0] * 1e-6,
                stresses[stresses.len() - 1] * 1e-6,
                strains[strains.len() - 1]
            ),
        }
    }
}

impl Hardening {
    /// Index of the linear segment holding `peeq` (for a table: `k` with
    /// `strains[k] ≤ peeq < strains[k+1]`, the last index meaning "past the table").
    pub fn segment(&self, peeq: f64) -> usize {
        match self {
            Self::Table { strains, .. } => strains.iter().rposition(|&e| e <= peeq).unwrap_or(0),
            _ => 0,
        }
    }

    /// Yield stress and slope `dσ_y/dε̄ᵖ` on segment `k`, evaluated at `peeq`.
    pub(crate) fn on_segment(&self, k: usize, peeq: f64) -> (f64, f64) {
        match self {
            Self::Perfect { yield_stress } => (*yield_stress, 0.0),
            Self::Linear { yield_stress, modulus } => (yield_stress + modulus * peeq, *modulus),
            Self::Voce { yield_stress, saturation, rate } => {
                let decay = (-rate * peeq).exp();
                (yield_stress + saturation * (1.0 - decay), saturation * rate * decay)
            }
            Self::Table { strains, stresses } => {
                if k + 1 >= strains.len() {
                    (*stresses.last().unwrap(), 0.0)
                } else {
                    let h = (stresses[k + 1] - stresses[k]) / (strains[k + 1] - strains[k]);
                    (stresses[k] + h * (peeq - strains[k]), h)
                }
            }
        }
    }

    /// Upper end of segment `k` (infinite for the last one).
    pub(crate) fn segment_end(&self, k: usize) -> f64 {
        match self {
            Self::Table { strains, .. } if k + 1 < strains.len() => strains[k + 1],
            _ => f64::INFINITY,
        }
    }

    /// Yield stress and slope at `peeq` (slope of the segment to the right of a break).
    pub fn eval(&self, peeq: f64) -> (f64, f64) {
        self.on_segment(self.segment(peeq), peeq)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_interpolated_and_constant_past_the_end() {
        let h = Hardening::Table { strains: vec![0.0, 0.01, 0.03], stresses: vec![100e6, 120e6, 130e6] };
        assert_eq!(h.eval(0.0), (100e6, 2e9));
        let (s, d) = h.eval(0.02);
        assert!((s - 125e6).abs() < 1e-6 && (d - 0.5e9).abs() < 1e-3);
        assert_eq!(h.eval(0.5), (130e6, 0.0));
    }
}
