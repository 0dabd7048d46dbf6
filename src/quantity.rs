//! Named result quantities, as used in model files, CSV headers and plots,
//! and the fields at one point ([`Sample`]).

use crate::voigt::Voigt;

/// A scalar result quantity at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Displacement component `u_x`, `u_y`, `u_z` (index 0–2), m.
    Displacement(usize),
    /// Total strain in Voigt order (engineering shear), −.
    Strain(usize),
    /// Stress in Voigt order, Pa.
    Stress(usize),
    /// Von Mises stress, Pa.
    VonMises,
    /// Equivalent plastic strain, −.
    Peeq,
    /// A failure index (`crate::materials::failure::CRITERIA`: maximum stress,
    /// Tsai–Wu, Hashin fibre, Hashin matrix), −; 0 where the material has
    /// no strengths.
    Failure(usize),
}

const VOIGT: [&str; 6] = ["xx", "yy", "zz", "xy", "xz", "yz"];
const AXES: [&str; 3] = ["x", "y", "z"];

impl Quantity {
    /// Every quantity, in CSV column order.
    pub fn all() -> Vec<Quantity> {
        let mut v: Vec<Quantity> = (0..3).map(Quantity::Displacement).collect();
        v.extend((0..6).map(Quantity::Stress));
        v.push(Quantity::VonMises);
        v.push(Quantity::Peeq);
        v.extend((0..6).map(Quantity::Strain));
        v
    }

    /// [`Quantity::all`], followed by the failure indices when `failure`
    /// (a model with strengths).
    pub(crate) fn all_for(failure: bool) -> Vec<Quantity> {
        let mut v = Self::all();
        if failure {
            v.extend((0..4).map(Quantity::Failure));
        }
        v
    }

    /// Model-file / CSV name (`u_z`, `s_yy`, `e_xz`, `von_mises`, `peeq`, `fi_tsai_wu`).
    pub fn name(self) -> String {
        match self {
            Self::Displacement(k) => format!("u_{}", AXES[k]),
            Self::Strain(k) => format!("e_{}", VOIGT[k]),
            Self::Stress(k) => format!("s_{}", VOIGT[k]),
            Self::VonMises => "von_mises".into(),
            Self::Peeq => "peeq".into(),
            Self::Failure(k) => crate::materials::failure::CRITERIA[k].into(),
        }
    }

    /// Parses a name produced by [`Quantity::name`].
    pub fn parse(s: &str) -> Option<Self> {
        Self::all_for(true).into_iter().find(|q| q.name() == s)
    }

    /// Human label with unit, for plots and tables.
    pub fn label(self) -> String {
        match self {
            Self::Displacement(k) => format!("u_{} [mm]", AXES[k]),
            Self::Strain(k) => format!("ε_{} [-]", VOIGT[k]),
            Self::Stress(k) => format!("σ_{} [MPa]", VOIGT[k]),
            Self::VonMises => "von Mises stress [MPa]".into(),
            Self::Peeq => "equivalent plastic strain [-]".into(),
            Self::Failure(k) => format!("failure index {} [-]", &crate::materials::failure::CRITERIA[k][3..]),
        }
    }

    /// Factor from SI to the display unit of [`Quantity::label`].
    pub fn display_scale(self) -> f64 {
        match self {
            Self::Displacement(_) => 1e3,
            Self::Stress(_) | Self::VonMises => 1e-6,
            _ => 1.0,
        }
    }
}

/// All fields at one point of a body.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Displacement (m).
    pub u: [f64; 3],
    /// Total strain (Voigt, engineering shear).
    pub strain: Voigt,
    /// Stress (Pa).
    pub stress: Voigt,
    /// Von Mises stress (Pa).
    pub von_mises: f64,
    /// Equivalent plastic strain.
    pub peeq: f64,
    /// Failure indices (`crate::materials::failure::CRITERIA`), 0 without strengths.
    pub failure: [f64; 4],
}

impl Sample {
    /// Value of a quantity.
    pub fn get(&self, q: Quantity) -> f64 {
        match q {
            Quantity::Displacement(k) => self.u[k],
            Quantity::Strain(k) => self.strain[k],
            Quantity::Stress(k) => self.stress[k],
            Quantity::VonMises => self.von_mises,
            Quantity::Peeq => self.peeq,
            Quantity::Failure(k) => self.failure[k],
        }
    }

    /// Component-wise mean of samples (used where a point lies on the
    /// boundary of several elements). The von Mises stress is that of the
    /// mean stress tensor, so the reported invariant always belongs to the
    /// reported tensor (averaging the elements' own von Mises values gave
    /// 92.5 MPa beside a tensor whose invariant is 82.1 MPa at the block's
    /// punch edge). The failure indices are the largest of the samples'
    /// (a point on a ply interface fails when either ply does).
    pub fn mean(samples: &[Sample]) -> Sample {
        let n = samples.len() as f64;
        let mut m = Sample::default();
        for s in samples {
            for k in 0..3 {
                m.u[k] += s.u[k] / n;
            }
            for k in 0..6 {
                m.strain[k] += s.strain[k] / n;
                m.stress[k] += s.stress[k] / n;
            }
            m.peeq += s.peeq / n;
            for k in 0..4 {
                m.failure[k] = m.failure[k].max(s.failure[k]);
            }
        }
        m.von_mises = crate::voigt::von_mises(&m.stress);
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_reports_the_von_mises_stress_of_the_mean_tensor() {
        // two elements meeting at a point: uniaxial ±σ in different directions
        let mut a = Sample { stress: [100.0, 0.0, 0.0, 0.0, 0.0, 0.0], ..Default::default() };
        a.von_mises = crate::voigt::von_mises(&a.stress);
        let mut b = Sample { stress: [0.0, 100.0, 0.0, 0.0, 0.0, 0.0], ..Default::default() };
        b.von_mises = crate::voigt::von_mises(&b.stress);
        let m = Sample::mean(&[a, b]);
        // mean tensor diag(50, 50, 0): von Mises 50, not the mean of 100 and 100
        assert!((m.von_mises - 50.0).abs() < 1e-12, "{}", m.von_mises);
    }

    #[test]
    fn names_round_trip() {
        for q in Quantity::all() {
            assert_eq!(Quantity::parse(&q.name()), Some(q));
        }
        assert_eq!(Quantity::parse("s_zz"), Some(Quantity::Stress(2)));
        assert_eq!(Quantity::parse("sigma"), None);
    }
}
