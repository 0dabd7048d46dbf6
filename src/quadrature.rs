//! Gauss–Legendre quadrature on `[-1, 1]` and its tensor products.
//!
//! An `n`-point rule integrates polynomials of degree `2n - 1` exactly. The
//! CUF element of order `p` along a direction uses `p + 1` points there
//! ("full" integration: for parallelogram sections and a straight axis the
//! stiffness integrand `∂N ∂N` has degree at most `2p` per direction and is
//! integrated exactly; for general quadrilaterals it is rational and the rule
//! is the usual approximation).
//!
//! Points and weights are computed by Newton's method on the Legendre
//! polynomial `P_n` (Press et al., *Numerical Recipes*, §4.6), accurate to
//! round-off for the small `n` used here.

/// A one-dimensional Gauss–Legendre rule on `[-1, 1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct GaussRule {
    /// Abscissae in increasing order.
    pub points: Vec<f64>,
    /// Weights, summing to 2.
    pub weights: Vec<f64>,
}

impl GaussRule {
    /// The `n`-point rule (`n ≥ 1`).
    ///
    /// # Panics
    /// If `n == 0`; callers derive `n` from element orders, never from input.
    pub fn new(n: usize) -> Self {
        assert!(n >= 1, "a Gauss rule needs at least one point");
        let mut points = vec![0.0; n];
        let mut weights = vec![0.0; n];
        let nf = n as f64;
        for i in 0..n.div_ceil(2) {
            // Chebyshev-like first guess of the i-th root (from the right).
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (p, d) = legendre_with_derivative(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre_with_derivative(n, x);
            dp = if d != 0.0 { d } else { dp };
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            points[i] = -x;
            points[n - 1 - i] = x;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        if n % 2 == 1 {
            points[n / 2] = 0.0;
        }
        Self { points, weights }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Always false: a rule has at least one point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

/// Legendre polynomial `P_n(x)` and its derivative by the three-term recurrence.
fn legendre_with_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

/// A tensor-product rule on the square `[-1, 1]²`, ξ varying fastest.
#[derive(Debug, Clone)]
pub struct SquareRule {
    /// `(ξ, η)` of each point.
    pub points: Vec<[f64; 2]>,
    /// Weights, summing to 4.
    pub weights: Vec<f64>,
}

impl SquareRule {
    /// The `n × n` Gauss rule.
    pub fn new(n: usize) -> Self {
        let g = GaussRule::new(n);
        let mut points = Vec::with_capacity(n * n);
        let mut weights = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                points.push([g.points[i], g.points[j]]);
                weights.push(g.weights[i] * g.weights[j]);
            }
        }
        Self { points, weights }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Always false: a rule has at least one point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_two_and_three_point_rules() {
        // Abramowitz & Stegun, Table 25.4.
        let g = GaussRule::new(2);
        assert!((g.points[1] - 1.0 / 3f64.sqrt()).abs() < 1e-15);
        assert!((g.weights[0] - 1.0).abs() < 1e-15);
        let g = GaussRule::new(3);
        assert!((g.points[2] - 0.6f64.sqrt()).abs() < 1e-15);
        assert!((g.weights[1] - 8.0 / 9.0).abs() < 1e-15);
        assert!((g.weights[0] - 5.0 / 9.0).abs() < 1e-15);
    }

    #[test]
    fn n_point_rule_is_exact_to_degree_2n_minus_1() {
        for n in 1..=8 {
            let g = GaussRule::new(n);
            for deg in 0..2 * n {
                let exact = if deg % 2 == 1 { 0.0 } else { 2.0 / (deg as f64 + 1.0) };
                let q: f64 = g.points.iter().zip(&g.weights).map(|(x, w)| w * x.powi(deg as i32)).sum();
                assert!((q - exact).abs() < 1e-14, "n={n} deg={deg}: {q} vs {exact}");
            }
            // and not exact at degree 2n
            let deg = 2 * n;
            let q: f64 = g.points.iter().zip(&g.weights).map(|(x, w)| w * x.powi(deg as i32)).sum();
            assert!((q - 2.0 / (deg as f64 + 1.0)).abs() > 1e-6);
        }
    }

    #[test]
    fn square_rule_weights_sum_to_area() {
        let r = SquareRule::new(3);
        assert_eq!(r.len(), 9);
        assert!((r.weights.iter().sum::<f64>() - 4.0).abs() < 1e-14);
    }
}
