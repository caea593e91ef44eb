//! Vectors and quaternions in f64 lanes (any `vsrlab_lanes::Lanes` form: the portable arrays or
//! AVX2 registers): one per episode of a population stepped together, each operation term for
//! term as glam's, so that a lane gives glam's bits.

use vsrlab_lanes::Lanes;

/// A vector per lane: `x`, `y`, `z` each hold every lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct V3<L: Lanes> {
    pub x: L,
    pub y: L,
    pub z: L,
}

impl<L: Lanes> V3<L> {
    /// The same vector in every lane.
    pub fn splat(v: glam::DVec3) -> Self {
        V3 {
            x: L::splat(v.x),
            y: L::splat(v.y),
            z: L::splat(v.z),
        }
    }

    /// Lane `l` as a glam vector.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> glam::DVec3 {
        glam::DVec3::new(self.x.get(l), self.y.get(l), self.z.get(l))
    }

    /// Sets lane `l`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, v: glam::DVec3) {
        self.x.set(l, v.x);
        self.y.set(l, v.y);
        self.z.set(l, v.z);
    }

    /// Component by component: `then` where `mask` holds, else `otherwise`.
    #[inline(always)]
    pub fn select(mask: L::Mask, then: Self, otherwise: Self) -> Self {
        V3 {
            x: L::select(mask, then.x, otherwise.x),
            y: L::select(mask, then.y, otherwise.y),
            z: L::select(mask, then.z, otherwise.z),
        }
    }

    /// Component by component `self + o` (glam's `DVec3 + DVec3`).
    #[inline(always)]
    pub fn add(self, o: Self) -> Self {
        V3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }

    /// Component by component `self - o`.
    #[inline(always)]
    pub fn sub(self, o: Self) -> Self {
        V3 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    /// `s * self` (glam's `f64 * DVec3`).
    #[inline(always)]
    pub fn scale(self, s: L) -> Self {
        V3 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }

    /// glam's `length`: `sqrt(x·x + y·y + z·z)`.
    #[inline(always)]
    pub fn length(self) -> L {
        (self.x * self.x + self.y * self.y + self.z * self.z).sqrt()
    }
}

/// A quaternion per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Q<L: Lanes> {
    pub x: L,
    pub y: L,
    pub z: L,
    pub w: L,
}

impl<L: Lanes> Q<L> {
    /// The same quaternion in every lane.
    pub fn splat(q: glam::DQuat) -> Self {
        Q {
            x: L::splat(q.x),
            y: L::splat(q.y),
            z: L::splat(q.z),
            w: L::splat(q.w),
        }
    }

    /// Lane `l` as a glam quaternion.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> glam::DQuat {
        glam::DQuat::from_xyzw(self.x.get(l), self.y.get(l), self.z.get(l), self.w.get(l))
    }

    /// Sets lane `l`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, q: glam::DQuat) {
        self.x.set(l, q.x);
        self.y.set(l, q.y);
        self.z.set(l, q.z);
        self.w.set(l, q.w);
    }

    /// Component by component: `then` where `mask` holds, else `otherwise`.
    #[inline(always)]
    pub fn select(mask: L::Mask, then: Self, otherwise: Self) -> Self {
        Q {
            x: L::select(mask, then.x, otherwise.x),
            y: L::select(mask, then.y, otherwise.y),
            z: L::select(mask, then.z, otherwise.z),
            w: L::select(mask, then.w, otherwise.w),
        }
    }

    /// The conjugate (glam's `conjugate`).
    #[inline(always)]
    pub fn conjugate(self) -> Self {
        Q {
            x: -self.x,
            y: -self.y,
            z: -self.z,
            w: self.w,
        }
    }

    /// The Hamilton product `self * o`, term for term as glam's `DQuat::mul_quat`.
    #[inline(always)]
    pub fn mul(self, o: Self) -> Self {
        let (x0, y0, z0, w0) = (self.x, self.y, self.z, self.w);
        let (x1, y1, z1, w1) = (o.x, o.y, o.z, o.w);
        Q {
            x: w0 * x1 + x0 * w1 + y0 * z1 - z0 * y1,
            y: w0 * y1 - x0 * z1 + y0 * w1 + z0 * x1,
            z: w0 * z1 + x0 * y1 - y0 * x1 + z0 * w1,
            w: w0 * w1 - x0 * x1 - y0 * y1 - z0 * z1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_laned_quaternion_product_gives_glams_bits() {
        let q = Q::<vsrlab_lanes::F64s<2>>::splat(glam::DQuat::from_xyzw(0.1, -0.2, 0.3, 0.9));
        let p = Q::<vsrlab_lanes::F64s<2>>::splat(glam::DQuat::from_xyzw(-0.5, 0.4, 0.2, 0.7));
        assert_eq!(q.mul(p).lane(1), q.lane(1) * p.lane(1));
        assert_ne!(q.mul(p).lane(1), p.lane(1) * q.lane(1));
        let v = V3::<vsrlab_lanes::F64s<2>>::splat(glam::DVec3::new(0.3, -0.1, 2.0));
        assert_eq!(v.length().get(0), glam::DVec3::new(0.3, -0.1, 2.0).length());
    }
}
