//! The albedo table of `docs/brdf-models.md`: directional albedo at
//! θ_i = 0, 30, 60, 80, 89° for representative parameters of every model
//! and term, as Markdown (`gonio brdf --albedo-table`).
//!
//! Every glossy row isolates its lobe (`k_d = 0`, `k_s = 1`) so that the
//! number is the lobe's own energy balance; Fresnel is `none` unless the
//! row is about Fresnel, so the distribution and geometry terms are seen
//! alone. Values are the mean of R, G, B (all rows are grey but the
//! coloured presets, which are grey in the lecture's tables too).

use super::albedo::{AlbedoEstimate, directional_albedo};
use super::spec;
use crate::Result;
use rayon::prelude::*;

/// The incidence angles of the table, degrees.
pub const ANGLES_DEG: [f64; 5] = [0.0, 30.0, 60.0, 80.0, 89.0];

/// The rows: a material spec (see [`spec::compare_spec`]) and a remark,
/// from each model's `albedo_table` in the table of models.
pub fn specs() -> Vec<(String, &'static str)> {
    crate::material::table::ROWS
        .iter()
        .flat_map(|row| {
            row.albedo_table
                .iter()
                .map(move |(params, remark)| (format!("{},{params}", row.model), *remark))
        })
        .collect()
}

/// One computed row.
pub struct Row {
    pub spec: String,
    pub remark: &'static str,
    pub estimates: Vec<AlbedoEstimate>,
}

/// Computes every row (in parallel).
pub fn compute() -> Result<Vec<Row>> {
    let materials = specs()
        .into_iter()
        .map(|(s, r)| {
            let m = spec::compare_spec(&s, &[])?.material;
            Ok((s, r, m))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(materials
        .par_iter()
        .map(|(spec, remark, m)| Row {
            spec: spec.clone(),
            remark,
            estimates: ANGLES_DEG
                .iter()
                .map(|d| directional_albedo(m, d.to_radians()))
                .collect(),
        })
        .collect())
}

/// The rows as a Markdown table: model, parameters, ρ at each angle
/// (values above 1 in bold), the largest error bound, remark.
pub fn markdown(rows: &[Row]) -> String {
    let mean = |v: glam::DVec3| (v.x + v.y + v.z) / 3.0;
    let mut out = String::from("| model | parameters |");
    for a in ANGLES_DEG {
        out += &format!(" ρ({a}°) |");
    }
    out += " error ≤ | note |\n|---|---|";
    out += &"---:|".repeat(ANGLES_DEG.len());
    out += "---:|---|\n";
    for row in rows {
        let (model, params) = row.spec.split_once(',').unwrap_or((&row.spec, ""));
        let params = params
            .split(',')
            .filter(|p| !matches!(*p, "k_d=0" | "k_s=1"))
            .collect::<Vec<_>>()
            .join(", ");
        out += &format!("| `{model}` | {params} |");
        for e in &row.estimates {
            let v = mean(e.value);
            if v > 1.0 + mean(e.error_bound) {
                out += &format!(" **{v:.4}** |");
            } else {
                out += &format!(" {v:.4} |");
            }
        }
        let worst = row
            .estimates
            .iter()
            .map(|e| mean(e.error_bound))
            .fold(0.0, f64::max);
        let worst = if worst == 0.0 {
            "0".to_string()
        } else {
            format!("{worst:.0e}")
        };
        out += &format!(" {worst} | {} |\n", row.remark);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_row_parses() {
        for (s, _) in specs() {
            spec::compare_spec(&s, &[]).unwrap_or_else(|e| panic!("{s}: {e}"));
        }
    }
}
