//! The functions of the rigid-bottom model, exactly.
//!
//! A rigid mass under an elastic stack obeys `m dV/dt = Z (2 beta - V)`,
//! one linear ODE with one rate `lambda = Z / m`; the stack above is a
//! lossless delay network. Starting from constants, every wave and every
//! velocity is therefore, piece by piece, `P(s) + Q(s) exp(-lambda s)` with
//! polynomials `P`, `Q` and `s` the time since the piece began: the ODE
//! maps the class into itself (raising the degree by one where the forcing
//! resonates with `exp(-lambda s)`), and so do delays, sums and integrals.
//! Nothing is discretised.

/// `P(s) + Q(s) exp(-lambda s)`, with `lambda` kept by the caller (one rate
/// for the whole model).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExpPoly {
    /// `P`'s coefficients, `p[k] s^k`.
    pub p: Vec<f64>,
    /// `Q`'s coefficients, `q[k] s^k exp(-lambda s)`.
    pub q: Vec<f64>,
}

fn horner(c: &[f64], s: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &x| acc * s + x)
}

fn add_into(a: &mut Vec<f64>, b: &[f64], scale: f64) {
    if a.len() < b.len() {
        a.resize(b.len(), 0.0);
    }
    for (x, y) in a.iter_mut().zip(b) {
        *x += scale * y;
    }
}

/// `k!` as a float.
fn factorial(k: usize) -> f64 {
    (1..=k).map(|i| i as f64).product()
}

impl ExpPoly {
    /// The constant `c` (no exponential part).
    pub fn constant(c: f64) -> Self {
        Self {
            p: vec![c],
            q: vec![],
        }
    }

    /// `c exp(-lambda s)`.
    pub fn decay(c: f64) -> Self {
        Self {
            p: vec![],
            q: vec![c],
        }
    }

    /// `f(s)`, as `(P + Q)(s) + Q(s) (exp(-lambda s) - 1)`: near `s = 0`
    /// the two parts of an integral (`P(0) = -Q(0)`) cancel exactly in
    /// their coefficients instead of in rounded values, so a height that
    /// starts at zero is positive at once when the velocity is.
    pub fn eval(&self, s: f64, lambda: f64) -> f64 {
        let q = horner(&self.q, s);
        if q == 0.0 {
            return horner(&self.p, s);
        }
        let n = self.p.len().max(self.q.len());
        let sum = (0..n).rev().fold(0.0, |acc, k| {
            let c = self.p.get(k).copied().unwrap_or(0.0) + self.q.get(k).copied().unwrap_or(0.0);
            acc * s + c
        });
        sum + q * (-lambda * s).exp_m1()
    }

    /// `a self + b other`.
    pub fn combine(&self, a: f64, other: &ExpPoly, b: f64) -> ExpPoly {
        let mut out = ExpPoly::default();
        add_into(&mut out.p, &self.p, a);
        add_into(&mut out.p, &other.p, b);
        add_into(&mut out.q, &self.q, a);
        add_into(&mut out.q, &other.q, b);
        out
    }

    /// `a self`.
    pub fn scaled(&self, a: f64) -> ExpPoly {
        self.combine(a, &ExpPoly::default(), 0.0)
    }

    /// `g(s) = f(s + delta)`: the same function, its origin moved `delta`
    /// later.
    pub fn rebased(&self, delta: f64, lambda: f64) -> ExpPoly {
        if delta == 0.0 {
            return self.clone();
        }
        let shift = |c: &[f64]| {
            // c(s + d) = sum_k c_k sum_j C(k, j) s^j d^(k - j)
            let mut out = vec![0.0; c.len()];
            for (k, &ck) in c.iter().enumerate() {
                let mut binom = 1.0;
                let mut dpow = delta.powi(k as i32);
                for (j, slot) in out.iter_mut().enumerate().take(k + 1) {
                    *slot += ck * binom * dpow;
                    binom *= (k - j) as f64 / (j + 1) as f64;
                    dpow = if delta != 0.0 { dpow / delta } else { 0.0 };
                }
            }
            out
        };
        let decay = (-lambda * delta).exp();
        ExpPoly {
            p: shift(&self.p),
            q: if decay == 0.0 {
                vec![]
            } else {
                shift(&self.q).into_iter().map(|c| c * decay).collect()
            },
        }
    }

    /// `F(s) = integral_0^s f(u) du`.
    pub fn integral(&self, lambda: f64) -> ExpPoly {
        let mut out = ExpPoly {
            p: vec![0.0],
            q: vec![],
        };
        for (k, &c) in self.p.iter().enumerate() {
            add_into(&mut out.p, &monomial(k + 1, c / (k + 1) as f64), 1.0);
        }
        // integral_0^s u^k e^{-lu} du = k!/l^(k+1)
        //                               - e^{-ls} sum_j k!/(k-j)! s^(k-j) / l^(j+1)
        for (k, &c) in self.q.iter().enumerate() {
            if c == 0.0 {
                continue;
            }
            let kf = factorial(k);
            out.p[0] += c * kf / lambda.powi(k as i32 + 1);
            let mut poly = vec![0.0; k + 1];
            for j in 0..=k {
                poly[k - j] -= c * kf / factorial(k - j) / lambda.powi(j as i32 + 1);
            }
            add_into(&mut out.q, &poly, 1.0);
        }
        out
    }

    /// The velocity `V(s)` of a mass with `V(0) = v0` driven by
    /// `V' = lambda (2 beta(s) - V)`, exactly.
    pub fn driven(v0: f64, beta: &ExpPoly, lambda: f64) -> ExpPoly {
        let mut out = ExpPoly::decay(v0);
        // 2 l e^{-ls} integral_0^s e^{lu} u^k du
        //   = 2 l [sum_j (-1)^j k!/(k-j)! s^(k-j) / l^(j+1) - (-1)^k k!/l^(k+1) e^{-ls}]
        for (k, &b) in beta.p.iter().enumerate() {
            if b == 0.0 {
                continue;
            }
            let kf = factorial(k);
            let mut poly = vec![0.0; k + 1];
            for j in 0..=k {
                let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                poly[k - j] +=
                    2.0 * lambda * b * sign * kf / factorial(k - j) / lambda.powi(j as i32 + 1);
            }
            add_into(&mut out.p, &poly, 1.0);
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            add_into(
                &mut out.q,
                &[-2.0 * lambda * b * sign * kf / lambda.powi(k as i32 + 1)],
                1.0,
            );
        }
        // 2 l e^{-ls} integral_0^s u^k du = 2 l s^(k+1)/(k+1) e^{-ls}
        for (k, &c) in beta.q.iter().enumerate() {
            add_into(
                &mut out.q,
                &monomial(k + 1, 2.0 * lambda * c / (k + 1) as f64),
                1.0,
            );
        }
        out
    }

    /// The size of the terms `eval` adds at `s`: the scale of its rounding.
    fn magnitude(&self, s: f64, lambda: f64) -> f64 {
        let n = self.p.len().max(self.q.len());
        let e = (-lambda * s).exp_m1().abs();
        (0..n)
            .map(|k| {
                let p = self.p.get(k).copied().unwrap_or(0.0);
                let q = self.q.get(k).copied().unwrap_or(0.0);
                ((p + q).abs() + q.abs() * e) * s.powi(k as i32)
            })
            .sum()
    }

    /// A bound on `|f(s)|` over `[0, span]` (`exp(-lambda s) <= 1`).
    pub fn bound(&self, span: f64) -> f64 {
        let b = |c: &[f64]| {
            c.iter()
                .enumerate()
                .map(|(k, x)| x.abs() * span.powi(k as i32))
                .sum::<f64>()
        };
        b(&self.p) + b(&self.q)
    }

    /// The derivative.
    pub fn derivative(&self, lambda: f64) -> ExpPoly {
        let d = |c: &[f64]| -> Vec<f64> {
            c.iter()
                .enumerate()
                .skip(1)
                .map(|(k, x)| k as f64 * x)
                .collect()
        };
        let mut q = d(&self.q);
        add_into(&mut q, &self.q, -lambda);
        ExpPoly { p: d(&self.p), q }
    }

    /// How a function that is zero at 0, and not above it at `from`, leaves
    /// zero: stepping out from `from` by doublings up to `span` until it
    /// stands clearly above or below the rounding of its terms. A mass
    /// lifting off from rest starts with height, speed and push all zero,
    /// so its height rises like `s^3`, under the rounding of its terms for
    /// a while: taken as a landing at once, at zero speed and pulled up, it
    /// lifted off again at the same instant, sixteen million times, until
    /// the budget was spent (a steel base under rubber, silicone and a steel
    /// top; `tests/limit.rs`).
    fn clear_of_rounding(&self, from: f64, span: f64, lambda: f64) -> Clear {
        let mut s = from;
        loop {
            let f = self.eval(s, lambda);
            let noise = 64.0 * f64::EPSILON * self.magnitude(s, lambda);
            if f > noise {
                return Clear::Above(s);
            }
            if f < -noise {
                return Clear::Below;
            }
            if s >= span {
                return Clear::Unresolved;
            }
            s = (2.0 * s).min(span);
        }
    }

    /// The first `s` in `(0, span]` where the function, positive at `0` (or
    /// zero there and rising), comes down to zero; `None` if it stays
    /// positive. Intervals are split until a second-order Taylor bound
    /// over each (value and slope at its start, a bound on the curvature)
    /// proves it has no zero, or a sign change is bracketed to `tolerance`,
    /// so no zero is jumped over; a zero touched with a vanishing slope
    /// (grazing) is returned where the intervals shrink below `tolerance`.
    /// Zero at `0` is a zero only if it goes clearly down from there; one
    /// that stays within rounding of zero all the way has none that can be
    /// told apart (`Clear`).
    pub fn first_zero(&self, span: f64, lambda: f64, tolerance: f64) -> Option<f64> {
        let slope = self.derivative(lambda);
        let curvature = slope.derivative(lambda);
        let mut lo = 0.0;
        if self.eval(0.0, lambda) <= 0.0 {
            // zero at the start: it must rise (to whatever order), or it is
            // already down
            lo = tolerance.min(span);
            if self.eval(lo, lambda) <= 0.0 {
                match self.clear_of_rounding(lo, span, lambda) {
                    Clear::Above(from) => lo = from,
                    Clear::Below => return Some(0.0),
                    Clear::Unresolved => return None,
                }
            }
        }
        // intervals still to examine, latest first on the stack
        let mut todo = vec![(lo, span)];
        let mut budget = 200_000;
        while let Some((a, b)) = todo.pop() {
            budget -= 1;
            let fa = self.eval(a, lambda);
            if fa <= 0.0 {
                return Some(a);
            }
            let h = b - a;
            let f1 = slope.eval(a, lambda);
            let m2 = curvature.rebased(a, lambda).bound(h);
            // f(a + x) >= fa + f1 x - m2 x^2 / 2, concave: least at an end
            if fa + f1 * h - 0.5 * m2 * h * h > 0.0 {
                continue;
            }
            let fb = self.eval(b, lambda);
            if h <= tolerance || budget == 0 {
                if fb <= 0.0 {
                    return Some(b);
                }
                // touched, not crossed: a grazing zero, if what is left is
                // within rounding of the terms that made it
                if fa <= 64.0 * f64::EPSILON * self.magnitude(a, lambda) {
                    return Some(a);
                }
                continue;
            }
            let mid = 0.5 * (a + b);
            todo.push((mid, b));
            todo.push((a, mid));
        }
        None
    }
}

/// How a function that starts at zero leaves it, as far as rounding shows.
enum Clear {
    /// Clearly above the rounding of its terms from this time.
    Above(f64),
    /// Clearly below: it goes down at once.
    Below,
    /// Within rounding of zero all the way: no zero that can be told apart.
    Unresolved,
}

/// `c s^k`.
fn monomial(k: usize, c: f64) -> Vec<f64> {
    let mut v = vec![0.0; k + 1];
    v[k] = c;
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> ExpPoly {
        ExpPoly {
            p: vec![0.5, -1.0, 0.25],
            q: vec![1.5, 2.0, -0.5],
        }
    }

    #[test]
    fn rebasing_moves_the_origin() {
        let f = sample();
        let l = 1.7;
        let g = f.rebased(0.6, l);
        for s in [0.0, 0.3, 1.1] {
            assert!((g.eval(s, l) - f.eval(s + 0.6, l)).abs() < 1e-12);
        }
    }

    #[test]
    fn integral_and_derivative_invert() {
        let f = sample();
        let l = 2.3;
        let big_f = f.integral(l);
        assert!(big_f.eval(0.0, l).abs() < 1e-14);
        let back = big_f.derivative(l);
        for s in [0.1, 0.7, 2.0] {
            assert!((back.eval(s, l) - f.eval(s, l)).abs() < 1e-12, "{s}");
        }
        // against a Simpson rule
        let n = 2000;
        let h = 1.5 / n as f64;
        let simpson: f64 = (0..=n)
            .map(|i| {
                let w = if i == 0 || i == n {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * f.eval(i as f64 * h, l)
            })
            .sum::<f64>()
            * h
            / 3.0;
        assert!((big_f.eval(1.5, l) - simpson).abs() < 1e-10);
    }

    #[test]
    fn the_driven_velocity_solves_its_ode() {
        let beta = sample();
        let l = 3.1;
        let v = ExpPoly::driven(0.8, &beta, l);
        assert!((v.eval(0.0, l) - 0.8).abs() < 1e-14);
        let dv = v.derivative(l);
        for s in [0.0, 0.2, 0.9, 2.5] {
            let lhs = dv.eval(s, l);
            let rhs = l * (2.0 * beta.eval(s, l) - v.eval(s, l));
            assert!(
                (lhs - rhs).abs() < 1e-10 * (1.0 + rhs.abs()),
                "{s}: {lhs} {rhs}"
            );
        }
    }

    #[test]
    fn appendix_c_flight() {
        // constant beta = -1/2 (v_b = 1), lambda = 1: V = (v0 + 1) e^{-s} - 1
        let v = ExpPoly::driven(1.0, &ExpPoly::constant(-0.5), 1.0);
        for s in [0.0, 0.5, 2.0] {
            assert!((v.eval(s, 1.0) - (2.0 * (-s).exp() - 1.0)).abs() < 1e-14);
        }
        // landing: height (1 + v0)(1 - e^{-s}) - s = 0, v0 = 1: s = 1.5936...
        let z = v.integral(1.0);
        let land = z.first_zero(10.0, 1.0, 1e-14).unwrap();
        assert!((2.0 * (1.0 - (-land).exp()) - land).abs() < 1e-12);
        assert!((land - 1.593_624_260_040_3).abs() < 1e-10, "{land}");
    }

    /// A mass lifting off at zero speed, pulled up: its height and speed
    /// zero, its acceleration `3e-4`, its height a difference of terms near
    /// 124 (a piece that began long before; the state in which a steel base
    /// under rubber, silicone and a steel top stalled the model). Its first
    /// zero is where it comes down again, found here by scanning its values
    /// where they stand clear of rounding; rounding hid the rise at the
    /// tolerance, and the start was taken as a landing.
    #[test]
    fn a_lift_off_from_rest_is_not_a_landing() {
        let l = 0.036_688_322_007_832_855;
        let v = ExpPoly {
            p: vec![-2.945_531_741_815_823_3],
            q: vec![
                2.945_531_741_815_823_3,
                0.108_380_579_140_919_89,
                -0.001_666_473_364_057_811_4,
                9.204_153_083_881_024e-6,
                -3.217_121_276_767_909_7e-10,
            ],
        };
        let z = v.integral(l);
        let tolerance = 1e-13;
        assert_eq!(v.eval(0.0, l), 0.0);
        assert!(v.derivative(l).eval(0.0, l) > 2e-4);
        // the premise: at the tolerance, rounding shows no rise
        assert!(z.eval(0.0, l) <= 0.0 && z.eval(tolerance, l) <= 0.0);
        // no landing before the next arrival, `4e-5` later
        assert_eq!(z.first_zero(4e-5, l, tolerance), None);
        // it comes down where its values change sign, scanned from 1e-2 on
        let mut a = 1e-2;
        assert!(z.eval(a, l) > 1e-9);
        while z.eval(a + 1e-2, l) > 0.0 {
            a += 1e-2;
        }
        let mut b = a + 1e-2;
        for _ in 0..60 {
            let mid = 0.5 * (a + b);
            if z.eval(mid, l) > 0.0 {
                a = mid
            } else {
                b = mid
            }
        }
        let landing = z.first_zero(50.0, l, tolerance).unwrap();
        assert!((landing - b).abs() < 1e-9, "{landing} against {b}");
    }
}
