//! A graph brain drawn over its body (thesis §4.1, Fig. 4.3): every neuron a dot inside its voxel
//! (sensing neurons small with a green rim, hidden ones black-rimmed, the actuator largest with an
//! orange rim), filled by its output (black −1, white +1); every edge a line, red for a positive
//! weight and blue for a negative one, more opaque the larger |w|. Neurons of one voxel sit on a
//! small grid inside it, in the order the brain lists them.

use crate::draw::{paint, stroke};
use tiny_skia::{FillRule, PathBuilder, Pixmap, Transform};
use vsrlab_physics::Vec2;

/// Where neuron k of `count` in a voxel with these corners (NW, NE, SE, SW) is drawn.
fn slot(poly: &[Vec2], k: usize, count: usize) -> Vec2 {
    if poly.len() != 4 {
        let n = poly.len().max(1) as f64;
        return poly.iter().fold(Vec2::new(0.0, 0.0), |a, &p| a + p) * (1.0 / n);
    }
    let side = (count as f64).sqrt().ceil().max(1.0) as usize;
    let (col, row) = (k % side, k / side);
    let inset = |i: usize| 0.15 + 0.7 * (i as f64 + 0.5) / side as f64;
    let (u, w) = (inset(col), inset(row));
    let (nw, ne, se, sw) = (poly[0], poly[1], poly[2], poly[3]);
    let bottom = sw + (se - sw) * u;
    let top = nw + (ne - nw) * u;
    top + (bottom - top) * w
}

/// Draws the graph: `neurons` (unit, kind), `edges` (source, target, weight), this step's
/// `outputs`, over the units' polygons; `px` maps world points to pixels.
pub(crate) fn draw_graph(
    pm: &mut Pixmap,
    polys: &[&[Vec2]],
    neurons: &[(usize, u8)],
    edges: &[(usize, usize, f32)],
    outputs: Option<&[f64]>,
    px: impl Fn(Vec2) -> (f32, f32),
    anti_alias: bool,
) {
    let mut per_unit = vec![0usize; polys.len()];
    let mut index_in_unit = Vec::with_capacity(neurons.len());
    for &(unit, _) in neurons {
        let k = per_unit.get(unit).copied().unwrap_or(0);
        if let Some(c) = per_unit.get_mut(unit) {
            *c += 1;
        }
        index_in_unit.push(k);
    }
    let at: Vec<Option<(f32, f32)>> = neurons
        .iter()
        .zip(&index_in_unit)
        .map(|(&(unit, _), &k)| polys.get(unit).map(|poly| px(slot(poly, k, per_unit[unit]))))
        .collect();
    let line = stroke(1.0);
    for &(a, b, w) in edges {
        let (Some(Some(p)), Some(Some(q))) = (at.get(a), at.get(b)) else {
            continue;
        };
        let strength = if w.is_finite() { (w.abs() / 2.0).min(1.0) } else { 0.0 };
        let alpha = (60.0 + 160.0 * strength) as u8;
        let colour = if w >= 0.0 {
            [200, 50, 30, alpha]
        } else {
            [30, 70, 210, alpha]
        };
        let mut pb = PathBuilder::new();
        pb.move_to(p.0, p.1);
        pb.line_to(q.0, q.1);
        if let Some(path) = pb.finish() {
            pm.stroke_path(&path, &paint(colour, anti_alias), &line, Transform::identity(), None);
        }
    }
    let rim = stroke(1.0);
    for (i, &(_, kind)) in neurons.iter().enumerate() {
        let Some(Some((x, y))) = at.get(i) else { continue };
        let (radius, rim_colour) = match kind {
            0 => (1.8, [30, 150, 60, 255]),
            2 => (3.2, [230, 140, 0, 255]),
            _ => (2.5, [20, 20, 20, 255]),
        };
        let out = outputs.and_then(|o| o.get(i)).map_or(0.0, |&o| o as f32);
        let grey = if out.is_finite() {
            ((out.clamp(-1.0, 1.0) + 1.0) * 127.5) as u8
        } else {
            0
        };
        let Some(dot) = PathBuilder::from_circle(*x, *y, radius) else {
            continue;
        };
        pm.fill_path(
            &dot,
            &paint([grey, grey, grey, 255], anti_alias),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
        pm.stroke_path(&dot, &paint(rim_colour, anti_alias), &rim, Transform::identity(), None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_of_one_voxel_are_distinct_and_inside_it() {
        let square = [
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 0.0),
        ];
        let points: Vec<Vec2> = (0..5).map(|k| slot(&square, k, 5)).collect();
        for (i, p) in points.iter().enumerate() {
            assert!(p.x > 0.1 && p.x < 0.9 && p.y > 0.1 && p.y < 0.9, "{p:?}");
            for q in &points[..i] {
                assert!((*p - *q).length() > 0.1, "{p:?} {q:?}");
            }
        }
        // the first slot is top left
        assert!(points[0].x < 0.5 && points[0].y > 0.5);
    }

    #[test]
    fn edges_and_neurons_change_pixels() {
        let square = [
            Vec2::new(0.0, 10.0),
            Vec2::new(10.0, 10.0),
            Vec2::new(10.0, 0.0),
            Vec2::new(0.0, 0.0),
        ];
        let polys: Vec<&[Vec2]> = vec![&square];
        let px = |p: Vec2| ((p.x * 10.0) as f32, (100.0 - p.y * 10.0) as f32);
        let draw = |edges: &[(usize, usize, f32)]| {
            let mut pm = Pixmap::new(100, 100).unwrap();
            draw_graph(&mut pm, &polys, &[(0, 0), (0, 2)], edges, Some(&[0.5, -0.5]), px, true);
            pm
        };
        let without = draw(&[]);
        let with = draw(&[(0, 1, 1.5)]);
        assert!(without.pixels().iter().any(|p| p.alpha() > 0), "neurons are drawn");
        assert_ne!(without.data(), with.data(), "an edge adds pixels");
    }
}
