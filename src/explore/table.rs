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

/// The rows: a material spec (see [`spec::compare_spec`]) and a remark.
pub const ROWS: &[(&str, &str)] = &[
    ("lambert,k_d=1", "albedo k_d exactly"),
    ("phong,k_d=0,k_s=1,k_e=1", "lecture form: ÷ I·N"),
    ("phong,k_d=0,k_s=1,k_e=10", "lecture form"),
    ("phong,k_d=0,k_s=1,k_e=100", "lecture form"),
    ("phong-normalized,k_d=0,k_s=1,k_e=1", "(k_e+2)/2π"),
    ("phong-normalized,k_d=0,k_s=1,k_e=10", ""),
    ("phong-normalized,k_d=0,k_s=1,k_e=100", ""),
    ("phong-normalized,k_d=0,k_s=1,k_e=10000", ""),
    ("blinn-phong,k_d=0,k_s=1,k_e=1", "lecture form: ÷ I·N"),
    ("blinn-phong,k_d=0,k_s=1,k_e=10", "lecture form"),
    ("blinn-phong,k_d=0,k_s=1,k_e=100", "lecture form"),
    ("blinn-phong-normalized,k_d=0,k_s=1,k_e=1", ""),
    ("blinn-phong-normalized,k_d=0,k_s=1,k_e=10", ""),
    ("blinn-phong-normalized,k_d=0,k_s=1,k_e=100", ""),
    ("blinn-phong-normalized,k_d=0,k_s=1,k_e=10000", ""),
    ("ward,k_d=0,k_s=1,sigma=0.05", "lecture form"),
    ("ward,k_d=0,k_s=1,sigma=0.2", "lecture form"),
    ("ward,k_d=0,k_s=1,sigma=0.5", "lecture form"),
    (
        "ward-anisotropic,k_d=0,k_s=1,sigma_x=0.05,sigma_y=0.3",
        "φ_i along σ_x",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=smith,roughness=0.05",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=smith,roughness=1",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=v-groove,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=none,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=smith,roughness=0.05",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=smith,roughness=1",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=v-groove,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=none,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=blinn-normalized,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=blinn-normalized,geometry=smith,roughness=1",
        "Smith G of the matched Beckmann slope",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=gaussian-normalized,geometry=smith,roughness=1",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=gaussian-normalized,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=blinn,geometry=smith,roughness=0.3",
        "lecture D, peak 1",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=gaussian,geometry=smith,roughness=0.3",
        "lecture D, peak 1",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=v-groove,denominator=lecture,roughness=0.3",
        "lecture: ÷ π(N·V)(N·I)",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,fresnel=none,distribution=blinn,geometry=v-groove,denominator=lecture,roughness=0.3",
        "all lecture terms",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,preset=gold,fresnel=conductor,roughness=0.3",
        "gold, exact Fresnel",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,preset=gold,fresnel=conductor-lecture,roughness=0.3",
        "gold, lecture Fresnel",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,preset=gold,fresnel=schlick,roughness=0.3",
        "gold, Schlick",
    ),
    (
        "cook-torrance,k_d=0,k_s=1,preset=glass,fresnel=dielectric,roughness=0.3",
        "glass 1.5",
    ),
    ("mirror,k_s=1,fresnel=none", "δ lobe, closed form"),
    ("mirror,preset=silver", "silver, exact Fresnel"),
];

/// One computed row.
pub struct Row {
    pub spec: &'static str,
    pub remark: &'static str,
    pub estimates: Vec<AlbedoEstimate>,
}

/// Computes every row (in parallel).
pub fn compute() -> Result<Vec<Row>> {
    let materials = ROWS
        .iter()
        .map(|(s, r)| Ok((*s, *r, spec::compare_spec(s, &[])?.material)))
        .collect::<Result<Vec<_>>>()?;
    Ok(materials
        .par_iter()
        .map(|(spec, remark, m)| Row {
            spec,
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
        let (model, params) = row.spec.split_once(',').unwrap_or((row.spec, ""));
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
        for (s, _) in ROWS {
            spec::compare_spec(s, &[]).unwrap_or_else(|e| panic!("{s}: {e}"));
        }
    }
}
