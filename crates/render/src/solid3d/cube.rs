//! A voxel as a cube: its six faces from centre, orientation and edge, and which of them a camera
//! at a given point sees.

use super::quat::Quat;
use super::vec3::Vec3;

/// A cube in world space.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cube {
    /// Its centre (m).
    pub centre: Vec3,
    /// Turns its body axes into world axes.
    pub orientation: Quat,
    /// Its edge (m).
    pub edge: f64,
}

/// One face of a cube: its outward normal, its centre and its corners in order around it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CubeFace {
    /// Outward unit normal.
    pub normal: Vec3,
    /// Centre of the face.
    pub centre: Vec3,
    /// Corners, in order around the face.
    pub corners: [Vec3; 4],
}

impl Cube {
    /// The six faces: −x, +x, −y, +y, −z, +z of the cube's own axes.
    pub fn faces(&self) -> [CubeFace; 6] {
        let h = self.edge / 2.0;
        let axes = [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ]
        .map(|a| self.orientation.rotate(a));
        std::array::from_fn(|i| {
            let (axis, sign) = (i / 2, if i % 2 == 0 { -1.0 } else { 1.0 });
            let normal = axes[axis] * sign;
            let u = axes[(axis + 1) % 3] * h;
            let v = axes[(axis + 2) % 3] * h;
            let centre = self.centre + normal * h;
            CubeFace {
                normal,
                centre,
                corners: [centre + u + v, centre - u + v, centre - u - v, centre + u - v],
            }
        })
    }

    /// The faces turned towards a viewer at `eye` (back faces culled).
    pub fn visible_faces(&self, eye: Vec3) -> impl Iterator<Item = CubeFace> {
        self.faces()
            .into_iter()
            .filter(move |f| f.normal.dot(eye - f.centre) > 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_cube() -> Cube {
        Cube {
            centre: Vec3::new(1.0, 2.0, 3.0),
            orientation: Quat::IDENTITY,
            edge: 2.0,
        }
    }

    #[test]
    fn faces_lie_on_the_cube_with_corners_at_its_vertices() {
        let cube = unit_cube();
        for face in cube.faces() {
            assert!(((face.centre - cube.centre).length() - 1.0).abs() < 1e-12);
            for corner in face.corners {
                let d = corner - cube.centre;
                assert!([d.x, d.y, d.z].iter().all(|c| (c.abs() - 1.0).abs() < 1e-12), "{d:?}");
                assert!(
                    (corner - face.centre).dot(face.normal).abs() < 1e-12,
                    "in the face's plane"
                );
            }
        }
    }

    #[test]
    fn a_viewer_above_in_front_and_right_sees_top_front_and_right() {
        let cube = unit_cube();
        let eye = cube.centre + Vec3::new(5.0, -5.0, 5.0);
        let seen: Vec<Vec3> = cube.visible_faces(eye).map(|f| f.normal).collect();
        assert_eq!(
            seen,
            [
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, -1.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0)
            ]
        );
    }

    #[test]
    fn a_turn_about_z_turns_the_side_faces() {
        let s = std::f64::consts::FRAC_PI_8.sin();
        let c = std::f64::consts::FRAC_PI_8.cos();
        let cube = Cube {
            orientation: Quat::from_slice(Some(&[c, 0.0, 0.0, s])),
            ..unit_cube()
        };
        let plus_x = cube.faces()[1].normal;
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((plus_x - Vec3::new(h, h, 0.0)).length() < 1e-12, "{plus_x:?}");
    }
}
