//! Corrected beam theory (CBT) of the three delamination specimens — double
//! cantilever beam (DCB, mode I), end-notched flexure (ENF, mode II) and
//! mixed-mode bending (MMB) — as a test oracle: compliance, energy release
//! rate, onset load and the whole load–displacement curve under displacement
//! control (linear up to onset, then the propagation branch G = G_c).
//! Pure arithmetic in SI units (m, N, Pa, J/m²); checked on its own by
//! `cargo test --release --test oracles_selfcheck -- cbt`.
//!
//! # Sources
//!
//! - Crack-length correction χ: J. G. Williams, "End corrections for
//!   orthotropic DCB specimens", Compos. Sci. Technol. 35 (1989) 367–376, in
//!   the closed form of S. Hashemi, A. J. Kinloch and J. G. Williams, Proc. R.
//!   Soc. Lond. A 427 (1990) 173–199, as ASTM D6671 (MMB, §11) prints it:
//!   `χ = √(E11/(11 G13) · [3 − 2(Γ/(1+Γ))²])`, `Γ = 1.18 √(E11 E22)/G13`.
//!   The mode-I crack is lengthened by χh, the mode-II one by 0.42χh
//!   (Y. Wang and J. G. Williams, "Corrections for mode II fracture toughness
//!   specimens of composite materials", Compos. Sci. Technol. 43 (1992)
//!   251–256; ASTM D6671 uses both offsets). Found through the search tool:
//!   ASTM D6671/D6671M-06 (its first page only) and public codes that print
//!   the same χ, Γ, 0.42χh and lever formula (a Williams-1989 `chi_williams`
//!   and an MMB lever/compliance script); the equations themselves could not
//!   be read in the papers, so every formula is also checked by its
//!   properties (`tests/oracles_selfcheck.rs`) and by an independent python3
//!   calculation (complementary energy of Euler–Bernoulli beams integrated
//!   numerically, G by differentiating the compliance, the MMB lever by
//!   bisection on the mode ratio).
//! - DCB: two cantilevers of length a + χh and bending stiffness E11 B h³/12
//!   loaded at their tips (ASTM D5528's modified beam theory with Δ = χh).
//! - ENF: three-point bending of span 2L, load P at mid-span, crack from the
//!   support at y = 0 (L. A. Carlsson, J. W. Gillespie and R. B. Pipes,
//!   J. Compos. Mater. 20 (1986) 594–604), with A = a + 0.42χh. For A ≤ L,
//!   `C = (2L³ + 3A³)/(8E11Bh³)`. For A ≥ L (the tip past the load) the
//!   complementary energy of the same beams gives
//!   `C = (8L³ − 3(2L − A)³)/(8E11Bh³)`. Both are written in the effective
//!   length A, so C and G are continuous at A = L (a = L − 0.42χh). Stable
//!   under displacement control iff A0 ≥ 3^(−1/3) L = 0.693 L.
//! - MMB: J. R. Reeder and J. H. Crews, AIAA J. 28 (1990) 1270–1276, as in
//!   ASTM D6671 (§11 and its lever-length equation): the lever load P at
//!   distance c from the mid-span saddle splits into a DCB opening load
//!   `P_I = P(3c − L)/(4L)` and an ENF mid-span load `P_II = P(c + L)/L`;
//!   the lever load point moves by δ = ∂U/∂P. Valid while the crack tip has
//!   not reached the saddle: A_II = a + 0.42χh ≤ L. Propagation follows the
//!   Benzeggagh–Kenane criterion (Compos. Sci. Technol. 56 (1996) 439–449)
//!   `G_c = G_Ic + (G_IIc − G_Ic)(G_II/G)^η` at the mode ratio of each a.
//!
//! Linear geometry throughout (no large-rotation correction of the MMB lever,
//! ASTM D6671 §11's F factor): the oracle is compared with cufem's
//! small-strain runs, like for like.
#![allow(dead_code)]

/// Elastic constants and toughness of a unidirectional specimen.
#[derive(Clone, Copy, Debug)]
pub struct Material {
    /// Modulus along the fibre (the beam axis), Pa.
    pub e11: f64,
    /// Transverse modulus, Pa.
    pub e22: f64,
    /// Transverse shear modulus in the fibre–normal plane, Pa.
    pub g13: f64,
    /// Mode I toughness G_Ic, J/m².
    pub gic: f64,
    /// Mode II toughness G_IIc, J/m².
    pub giic: f64,
    /// Benzeggagh–Kenane exponent η.
    pub bk_exponent: f64,
}

impl Material {
    /// AS4/PEEK as used in design48 §3 (after Camanho, Dávila & de Moura
    /// 2003; the oracle only needs plausible values, the tests compare like
    /// for like).
    pub fn as4_peek() -> Self {
        Material { e11: 122.7e9, e22: 10.1e9, g13: 5.5e9, gic: 969.0, giic: 1719.0, bk_exponent: 2.284 }
    }

    /// The same material with other toughnesses (the ±10 % mutations).
    pub fn with_toughness(self, gic: f64, giic: f64) -> Self {
        Material { gic, giic, ..self }
    }

    /// Williams' Γ = 1.18 √(E11 E22)/G13.
    pub fn gamma(&self) -> f64 {
        1.18 * (self.e11 * self.e22).sqrt() / self.g13
    }

    /// Williams' crack-length correction χ (dimensionless): the mode-I crack
    /// is longer by χh, h the arm thickness.
    pub fn chi(&self) -> f64 {
        let g = self.gamma();
        let r = g / (1.0 + g);
        (self.e11 / (11.0 * self.g13) * (3.0 - 2.0 * r * r)).sqrt()
    }

    /// Benzeggagh–Kenane toughness at the mode ratio `ratio` = G_II/G.
    pub fn bk_toughness(&self, ratio: f64) -> f64 {
        self.gic + (self.giic - self.gic) * ratio.powf(self.bk_exponent)
    }
}

/// Crack-length offset of mode I, χh (m), for arm thickness `h`.
pub fn mode_i_offset(m: &Material, h: f64) -> f64 {
    m.chi() * h
}

/// Crack-length offset of mode II, 0.42χh (m), Wang & Williams (1992).
pub fn mode_ii_offset(m: &Material, h: f64) -> f64 {
    0.42 * m.chi() * h
}

/// A specimen whose energy release rate is quadratic in the load,
/// G = P² g(a): the curve under displacement control follows from C(a), the
/// two release rates and the toughness at each crack length.
pub trait Specimen {
    /// Compliance δ/P at crack length `a` (m/N).
    fn compliance(&self, a: f64) -> f64;
    /// Mode I and mode II energy release rates (J/m²) at load `p`, crack `a`.
    fn release_rates(&self, p: f64, a: f64) -> (f64, f64);
    /// Toughness (J/m²) at crack length `a` (for MMB: BK at the mode ratio of `a`).
    fn toughness(&self, a: f64) -> f64;
    /// Largest crack length the closed form covers (m).
    fn crack_limit(&self) -> f64;

    /// Total energy release rate G = G_I + G_II (J/m²).
    fn release_rate(&self, p: f64, a: f64) -> f64 {
        let (gi, gii) = self.release_rates(p, a);
        gi + gii
    }

    /// Mode ratio G_II/G at crack length `a` (independent of the load).
    fn mode_ratio(&self, a: f64) -> f64 {
        let (gi, gii) = self.release_rates(1.0, a);
        gii / (gi + gii)
    }

    /// Load at which the crack of length `a` grows: G(P, a) = G_c(a).
    fn critical_load(&self, a: f64) -> f64 {
        (self.toughness(a) / self.release_rate(1.0, a)).sqrt()
    }

    /// The propagation branch in parametric form: (δ, P) with the crack at `a`.
    fn branch_point(&self, a: f64) -> (f64, f64) {
        let p = self.critical_load(a);
        (p * self.compliance(a), p)
    }

    /// Onset (δ_c, P_c) from the initial crack `a0`: the peak of the curve.
    fn onset(&self, a0: f64) -> (f64, f64) {
        self.branch_point(a0)
    }

    /// Whether the branch's δ grows with a from `a0` to the crack limit
    /// (stable under displacement control; 400 samples).
    fn stable_from(&self, a0: f64) -> bool {
        let n = 400;
        let lim = self.crack_limit();
        let mut last = self.branch_point(a0).0;
        (1..=n).all(|i| {
            let d = self.branch_point(a0 + (lim - a0) * i as f64 / n as f64).0;
            let up = d >= last;
            last = d;
            up
        })
    }

    /// Crack length on the branch at opening `delta` (δ_c ≤ δ ≤ δ at the
    /// crack limit), by bisection on the monotone branch. Panics when the
    /// branch snaps back (use `branch_point`) or δ is outside the branch.
    fn branch_crack(&self, a0: f64, delta: f64) -> f64 {
        assert!(self.stable_from(a0), "the branch from a0 = {a0} snaps back: compare with branch_point(a)");
        let (mut lo, mut hi) = (a0, self.crack_limit());
        let top = self.branch_point(hi).0;
        assert!(delta <= top, "δ = {delta} is past the crack limit (δ = {top} there)");
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.branch_point(mid).0 < delta {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// Load on the branch at opening `delta` (see `branch_crack`).
    fn branch_load(&self, a0: f64, delta: f64) -> f64 {
        self.critical_load(self.branch_crack(a0, delta))
    }

    /// The whole CBT curve from the initial crack `a0`: δ/C(a0) up to onset,
    /// then the propagation branch.
    fn load(&self, a0: f64, delta: f64) -> f64 {
        let (dc, _) = self.onset(a0);
        if delta <= dc { delta / self.compliance(a0) } else { self.branch_load(a0, delta) }
    }

    /// `n + 1` points (δ, P) of the whole curve, δ from 0 to `delta_max`.
    fn sample(&self, a0: f64, delta_max: f64, n: usize) -> Vec<(f64, f64)> {
        (0..=n)
            .map(|i| {
                let d = delta_max * i as f64 / n as f64;
                (d, self.load(a0, d))
            })
            .collect()
    }
}

/// The curve error: `max |P − P_CBT(δ)| / P_c` over the points
/// `(δ, P)` of a computed curve, P_c the CBT peak from `a0`.
pub fn curve_error<S: Specimen>(points: &[(f64, f64)], reference: &S, a0: f64) -> f64 {
    let (_, pc) = reference.onset(a0);
    points.iter().map(|&(d, p)| (p - reference.load(a0, d)).abs() / pc).fold(0.0, f64::max)
}

/// Double cantilever beam: opening loads ±P at the arm tips, δ the opening
/// of the load points.
#[derive(Clone, Copy, Debug)]
pub struct Dcb {
    /// Material.
    pub material: Material,
    /// Width B (m).
    pub width: f64,
    /// Arm thickness h (half the specimen thickness, m).
    pub arm: f64,
    /// Length from the load line to the far end (m): the crack limit.
    pub length: f64,
}

impl Dcb {
    /// Effective crack length A = a + χh.
    pub fn effective(&self, a: f64) -> f64 {
        a + mode_i_offset(&self.material, self.arm)
    }

    /// K = B √(G_Ic E11 h³/12): P A = K on the branch.
    fn branch_constant(&self) -> f64 {
        self.width * (self.material.gic * self.material.e11 * self.arm.powi(3) / 12.0).sqrt()
    }

    /// Closed-form onset load `P_c = (B/A0) √(G_Ic E11 h³/12)`.
    pub fn onset_load(&self, a0: f64) -> f64 {
        self.branch_constant() / self.effective(a0)
    }

    /// Closed-form branch `P(δ) = B √(8 (G_Ic E11 h³/12)^{3/2} / (E11 h³ δ))`.
    pub fn branch_load_closed(&self, delta: f64) -> f64 {
        let eh3 = self.material.e11 * self.arm.powi(3);
        self.width * (8.0 * (self.material.gic * eh3 / 12.0).powf(1.5) / (eh3 * delta)).sqrt()
    }

    /// Closed-form crack on the branch `a(δ) = (B/P) √(G_Ic E11 h³/12) − χh`.
    pub fn branch_crack_closed(&self, delta: f64) -> f64 {
        self.branch_constant() / self.branch_load_closed(delta) - mode_i_offset(&self.material, self.arm)
    }
}

impl Specimen for Dcb {
    /// `C = 8 A³/(E11 B h³)`.
    fn compliance(&self, a: f64) -> f64 {
        8.0 * self.effective(a).powi(3) / (self.material.e11 * self.width * self.arm.powi(3))
    }

    /// `G_I = 12 P² A²/(E11 B² h³)`, G_II = 0.
    fn release_rates(&self, p: f64, a: f64) -> (f64, f64) {
        let e = self.effective(a);
        (12.0 * p * p * e * e / (self.material.e11 * self.width.powi(2) * self.arm.powi(3)), 0.0)
    }

    fn toughness(&self, _a: f64) -> f64 {
        self.material.gic
    }

    fn crack_limit(&self) -> f64 {
        self.length
    }
}

/// End-notched flexure: supports at y = 0 and 2L, load P at y = L, crack
/// from y = 0; δ the load-point deflection.
#[derive(Clone, Copy, Debug)]
pub struct Enf {
    /// Material.
    pub material: Material,
    /// Width B (m).
    pub width: f64,
    /// Arm thickness h (half the specimen thickness, m).
    pub arm: f64,
    /// Half-span L (m).
    pub half_span: f64,
}

impl Enf {
    /// Effective crack length A = a + 0.42χh.
    pub fn effective(&self, a: f64) -> f64 {
        a + mode_ii_offset(&self.material, self.arm)
    }

    /// Crack length at which the tip (effective) reaches the load: A = L.
    pub fn crack_at_load(&self) -> f64 {
        self.half_span - mode_ii_offset(&self.material, self.arm)
    }

    /// Shortest initial crack that propagates stably under displacement
    /// control: A0 = 3^(−1/3) L.
    pub fn stable_crack(&self) -> f64 {
        3f64.powf(-1.0 / 3.0) * self.half_span - mode_ii_offset(&self.material, self.arm)
    }

    /// Closed-form onset load (A0 ≤ L): `P_c = 4 B h^{3/2} √(E11 G_IIc)/(3 A0)`.
    pub fn onset_load(&self, a0: f64) -> f64 {
        4.0 * self.width * self.arm.powf(1.5) * (self.material.e11 * self.material.giic).sqrt()
            / (3.0 * self.effective(a0))
    }

    /// The lever arm of the bending moment at the effective tip, divided by
    /// P/2: A before the load, 2L − A past it.
    fn tip_arm(&self, a: f64) -> f64 {
        let e = self.effective(a);
        if e <= self.half_span { e } else { 2.0 * self.half_span - e }
    }
}

impl Specimen for Enf {
    /// `(2L³ + 3A³)/(8E11Bh³)` for A ≤ L, `(8L³ − 3(2L − A)³)/(8E11Bh³)` past it.
    fn compliance(&self, a: f64) -> f64 {
        let (l, e) = (self.half_span, self.effective(a));
        let num =
            if e <= l { 2.0 * l.powi(3) + 3.0 * e.powi(3) } else { 8.0 * l.powi(3) - 3.0 * (2.0 * l - e).powi(3) };
        num / (8.0 * self.material.e11 * self.width * self.arm.powi(3))
    }

    /// `G_II = 9 P² A²/(16 E11 B² h³)` (A → 2L − A past the load), G_I = 0.
    fn release_rates(&self, p: f64, a: f64) -> (f64, f64) {
        let t = self.tip_arm(a);
        (0.0, 9.0 * p * p * t * t / (16.0 * self.material.e11 * self.width.powi(2) * self.arm.powi(3)))
    }

    fn toughness(&self, _a: f64) -> f64 {
        self.material.giic
    }

    /// 1 % of L short of the far support (G → 0 there, P → ∞).
    fn crack_limit(&self) -> f64 {
        1.99 * self.half_span - mode_ii_offset(&self.material, self.arm)
    }
}

/// Mixed-mode bending (ASTM D6671): lever load P at distance `lever` = c
/// beyond the mid-span saddle; δ the lever load point's displacement.
#[derive(Clone, Copy, Debug)]
pub struct Mmb {
    /// Material.
    pub material: Material,
    /// Width B (m).
    pub width: f64,
    /// Arm thickness h (half the specimen thickness, m).
    pub arm: f64,
    /// Half-span L (m).
    pub half_span: f64,
    /// Lever length c (m), c ≥ L/3 (c = L/3 is pure mode II).
    pub lever: f64,
}

impl Mmb {
    /// The lever c of ASTM D6671 for the mode ratio `ratio` = G_II/G at the
    /// crack `a0`: α = (1 − r)/r, β = (a0 + χh)/(a0 + 0.42χh),
    /// `c = L (12β² + 3α + 8β√(3α))/(36β² − 3α)`. As c → ∞ the ratio tends
    /// to 1/(1 + 12β²) (≈ 0.07): no lever reaches a smaller one (panics).
    pub fn lever_for_ratio(material: &Material, arm: f64, half_span: f64, a0: f64, ratio: f64) -> f64 {
        let alpha = (1.0 - ratio) / ratio;
        let beta = (a0 + mode_i_offset(material, arm)) / (a0 + mode_ii_offset(material, arm));
        let least = 1.0 / (1.0 + 12.0 * beta * beta);
        assert!(ratio > least && ratio <= 1.0, "G_II/G = {ratio}: an MMB lever reaches ({least}, 1] at a0 = {a0}");
        half_span * (12.0 * beta * beta + 3.0 * alpha + 8.0 * beta * (3.0 * alpha).sqrt())
            / (36.0 * beta * beta - 3.0 * alpha)
    }

    /// The specimen whose lever gives `ratio` at `a0`.
    pub fn for_ratio(material: Material, width: f64, arm: f64, half_span: f64, a0: f64, ratio: f64) -> Self {
        let lever = Self::lever_for_ratio(&material, arm, half_span, a0, ratio);
        Mmb { material, width, arm, half_span, lever }
    }

    /// The split of the lever load: (P_I, P_II) = (P(3c − L)/(4L), P(c + L)/L).
    pub fn split(&self, p: f64) -> (f64, f64) {
        let (c, l) = (self.lever, self.half_span);
        (p * (3.0 * c - l) / (4.0 * l), p * (c + l) / l)
    }

    /// Effective lengths (A_I, A_II) = (a + χh, a + 0.42χh).
    pub fn effective(&self, a: f64) -> (f64, f64) {
        (a + mode_i_offset(&self.material, self.arm), a + mode_ii_offset(&self.material, self.arm))
    }

    fn denominator(&self) -> f64 {
        self.material.e11 * self.width * self.arm.powi(3) * self.half_span.powi(2)
    }
}

impl Specimen for Mmb {
    /// `[4(3c − L)² A_I³ + (c + L)²(2L³ + 3A_II³)] / (8 E11 B h³ L²)`.
    fn compliance(&self, a: f64) -> f64 {
        let (c, l) = (self.lever, self.half_span);
        let (ai, aii) = self.effective(a);
        (4.0 * (3.0 * c - l).powi(2) * ai.powi(3) + (c + l).powi(2) * (2.0 * l.powi(3) + 3.0 * aii.powi(3)))
            / (8.0 * self.denominator())
    }

    /// `G_I = 12 P²(3c − L)² A_I²/(16 B² h³ L² E11)`,
    /// `G_II = 9 P²(c + L)² A_II²/(16 B² h³ L² E11)`.
    fn release_rates(&self, p: f64, a: f64) -> (f64, f64) {
        let (c, l) = (self.lever, self.half_span);
        let (ai, aii) = self.effective(a);
        let d = 16.0 * self.denominator() * self.width;
        (12.0 * p * p * (3.0 * c - l).powi(2) * ai * ai / d, 9.0 * p * p * (c + l).powi(2) * aii * aii / d)
    }

    /// BK at the mode ratio of `a` (the ratio drifts as the crack grows).
    fn toughness(&self, a: f64) -> f64 {
        self.material.bk_toughness(self.mode_ratio(a))
    }

    /// The effective mode-II tip reaches the saddle: a + 0.42χh = L.
    fn crack_limit(&self) -> f64 {
        self.half_span - mode_ii_offset(&self.material, self.arm)
    }
}
