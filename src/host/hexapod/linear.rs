//! 6 × 6 linear algebra for the hexapod's Jacobian: solve, inverse and the
//! 1-norm condition number, by Gaussian elimination with partial pivoting.
//! A linear-algebra crate would bring more build time than these 60 lines
//! save; the suite's 15 minutes are spent mostly compiling.

/// A 6 × 6 matrix, row-major.
pub type Matrix6 = [[f64; 6]; 6];

/// `x` with `m · x = b`, or `None` when `m` is singular (a pivot below
/// 1e-300 times the largest entry).
pub fn solve(m: &Matrix6, b: &[f64; 6]) -> Option<[f64; 6]> {
    let scale = m.iter().flatten().fold(0.0_f64, |acc, v| acc.max(v.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return None;
    }
    let mut a = *m;
    let mut x = *b;
    for col in 0..6 {
        let pivot = (col..6)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .expect("rows left");
        if a[pivot][col].abs() <= 1e-300 * scale {
            return None;
        }
        a.swap(col, pivot);
        x.swap(col, pivot);
        for row in col + 1..6 {
            let f = a[row][col] / a[col][col];
            for k in col..6 {
                a[row][k] -= f * a[col][k];
            }
            x[row] -= f * x[col];
        }
    }
    for col in (0..6).rev() {
        let tail: f64 = (col + 1..6).map(|k| a[col][k] * x[k]).sum();
        x[col] = (x[col] - tail) / a[col][col];
    }
    Some(x)
}

/// The inverse of `m`, or `None` when it is singular.
pub fn inverse(m: &Matrix6) -> Option<Matrix6> {
    let mut inv = [[0.0; 6]; 6];
    for col in 0..6 {
        let mut e = [0.0; 6];
        e[col] = 1.0;
        let x = solve(m, &e)?;
        for row in 0..6 {
            inv[row][col] = x[row];
        }
    }
    Some(inv)
}

/// The 1-norm (largest column sum of magnitudes).
pub fn norm1(m: &Matrix6) -> f64 {
    (0..6)
        .map(|col| (0..6).map(|row| m[row][col].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// The 1-norm condition number ‖m‖₁ ‖m⁻¹‖₁; infinite when `m` is
/// singular.
pub fn condition(m: &Matrix6) -> f64 {
    inverse(m).map_or(f64::INFINITY, |inv| norm1(m) * norm1(&inv))
}

/// `m · v`.
pub fn mul(m: &Matrix6, v: &[f64; 6]) -> [f64; 6] {
    m.map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
}
