//! Lagrange polynomials on equispaced nodes of `[-1, 1]` and their tensor
//! products on `[-1, 1]²`.

/// One-dimensional Lagrange basis of order `p` on equispaced nodes.
#[derive(Debug, Clone)]
pub(crate) struct Lagrange1d {
    nodes: Vec<f64>,
}

impl Lagrange1d {
    /// The basis of order `p ≥ 1` (`p + 1` nodes).
    pub fn new(order: usize) -> Self {
        let p = order.max(1);
        let nodes = (0..=p).map(|k| -1.0 + 2.0 * k as f64 / p as f64).collect();
        Self { nodes }
    }

    /// Node abscissae.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// Number of basis functions.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Values `n[k] = N_k(ξ)` and derivatives `dn[k] = dN_k/dξ`.
    /// Both slices must have `len()` entries.
    pub fn eval(&self, xi: f64, n: &mut [f64], dn: &mut [f64]) {
        let m = self.nodes.len();
        for k in 0..m {
            let xk = self.nodes[k];
            let mut val = 1.0;
            let mut der = 0.0;
            for j in 0..m {
                if j == k {
                    continue;
                }
                let denom = xk - self.nodes[j];
                // product rule: d/dξ Π (ξ - ξ_j)/(ξ_k - ξ_j)
                der = der * (xi - self.nodes[j]) / denom + val / denom;
                val *= (xi - self.nodes[j]) / denom;
            }
            n[k] = val;
            dn[k] = der;
        }
    }

    /// Second derivatives `ddn[k] = d²N_k/dξ²` (`len()` entries):
    /// `Σ_(j≠l, both ≠ k) Π_(m ∉ {k, j, l}) (ξ − ξ_m) / Π_(m≠k) (ξ_k − ξ_m)`.
    pub(crate) fn second_derivatives(&self, xi: f64, ddn: &mut [f64]) {
        let x = &self.nodes;
        let m = x.len();
        for k in 0..m {
            let denom: f64 = (0..m).filter(|&j| j != k).map(|j| x[k] - x[j]).product();
            let mut sum = 0.0;
            for j in (0..m).filter(|&j| j != k) {
                for l in (0..m).filter(|&l| l != k && l != j) {
                    sum += (0..m).filter(|&q| q != k && q != j && q != l).map(|q| xi - x[q]).product::<f64>();
                }
            }
            ddn[k] = sum / denom;
        }
    }
}

/// Tensor-product Lagrange basis on `[-1, 1]²` (ξ varies fastest).
#[derive(Debug, Clone)]
pub struct Lagrange2d {
    line: Lagrange1d,
}

impl Lagrange2d {
    /// The basis of order `p` per direction (`(p + 1)²` functions).
    pub fn new(order: usize) -> Self {
        Self { line: Lagrange1d::new(order) }
    }

    /// Number of basis functions.
    pub fn len(&self) -> usize {
        self.line.len() * self.line.len()
    }

    /// Always false.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Natural coordinates of local node `k`.
    pub fn node(&self, k: usize) -> [f64; 2] {
        let m = self.line.len();
        [self.line.nodes()[k % m], self.line.nodes()[k / m]]
    }

    /// Values `f[k]`, and derivatives `dxi[k] = ∂F_k/∂ξ`, `deta[k] = ∂F_k/∂η`.
    pub fn eval(&self, xi: f64, eta: f64, f: &mut [f64], dxi: &mut [f64], deta: &mut [f64]) {
        let m = self.line.len();
        let mut a = [0.0; 8];
        let mut da = [0.0; 8];
        let mut b = [0.0; 8];
        let mut db = [0.0; 8];
        self.line.eval(xi, &mut a[..m], &mut da[..m]);
        self.line.eval(eta, &mut b[..m], &mut db[..m]);
        for j in 0..m {
            for i in 0..m {
                let k = j * m + i;
                f[k] = a[i] * b[j];
                dxi[k] = da[i] * b[j];
                deta[k] = a[i] * db[j];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Second derivatives against central differences of the first, and
    /// zero sum (the basis reproduces constants and lines).
    #[test]
    fn second_derivatives_match_differences() {
        for p in 1..=3 {
            let l = Lagrange1d::new(p);
            let m = l.len();
            let (mut n, mut dp, mut dm, mut dd) = (vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m]);
            for xi in [-0.9, -0.3, 0.2, 0.75] {
                let h = 1e-6;
                l.eval(xi + h, &mut n, &mut dp);
                l.eval(xi - h, &mut n, &mut dm);
                l.second_derivatives(xi, &mut dd);
                for k in 0..m {
                    let fd = (dp[k] - dm[k]) / (2.0 * h);
                    assert!((dd[k] - fd).abs() < 1e-6, "p {p} k {k}: {} against {fd}", dd[k]);
                }
                assert!(dd.iter().sum::<f64>().abs() < 1e-10);
            }
        }
    }

    #[test]
    fn kronecker_delta_and_partition_of_unity_1d() {
        for p in 1..=3 {
            let l = Lagrange1d::new(p);
            let (mut n, mut dn) = (vec![0.0; p + 1], vec![0.0; p + 1]);
            for (k, &xk) in l.nodes().iter().enumerate() {
                l.eval(xk, &mut n, &mut dn);
                for (j, v) in n.iter().enumerate() {
                    assert!((v - if j == k { 1.0 } else { 0.0 }).abs() < 1e-14);
                }
            }
            for &x in &[-0.77, 0.1, 0.93] {
                l.eval(x, &mut n, &mut dn);
                assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
                assert!(dn.iter().sum::<f64>().abs() < 1e-13);
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let h = 1e-6;
        for p in 1..=3 {
            let l = Lagrange1d::new(p);
            let m = p + 1;
            let (mut n, mut dn, mut np, mut nm, mut tmp) =
                (vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m]);
            let x = 0.3141;
            l.eval(x, &mut n, &mut dn);
            l.eval(x + h, &mut np, &mut tmp);
            l.eval(x - h, &mut nm, &mut tmp);
            for k in 0..m {
                let fd = (np[k] - nm[k]) / (2.0 * h);
                assert!((fd - dn[k]).abs() < 1e-8, "p={p} k={k}");
            }
        }
    }

    #[test]
    fn reproduces_polynomials_of_its_order_2d() {
        // Interpolating f = (1 + 2ξ - η)^p at the nodes reproduces it exactly.
        for p in 1..=3 {
            let l = Lagrange2d::new(p);
            let m = l.len();
            let f = |x: f64, y: f64| (1.0 + 2.0 * x - y).powi(p as i32);
            let vals: Vec<f64> = (0..m).map(|k| l.node(k)).map(|[x, y]| f(x, y)).collect();
            let (mut n, mut dx, mut dy) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
            let (x, y) = (0.37, -0.58);
            l.eval(x, y, &mut n, &mut dx, &mut dy);
            let interp: f64 = n.iter().zip(&vals).map(|(a, b)| a * b).sum();
            assert!((interp - f(x, y)).abs() < 1e-12, "p={p}");
            let dfdx: f64 = dx.iter().zip(&vals).map(|(a, b)| a * b).sum();
            let exact = 2.0 * p as f64 * (1.0 + 2.0 * x - y).powi(p as i32 - 1);
            assert!((dfdx - exact).abs() < 1e-11);
        }
    }
}
