//! A pinhole camera that turns pixel positions into primary rays, with the
//! formulas of the ray caster's camera (the course framework's), so that
//! the benches' camera rays are the rays the ray caster shoots.
//!
//! With `d = normalize(direction)`:
//!
//! - `horizontal = normalize(d × up)` and `up' = horizontal × d`, a
//!   right-handed frame with `d` looking into the image;
//! - the focal length in pixels is `f = height / (2·tan(angle/2))`, `angle`
//!   being the vertical field of view;
//! - the image position `(sx, sy)` in pixels, measured from the top-left
//!   corner of the image (row 0 at the top, so a pixel `(x, y)` covers
//!   `[x, x+1) × [y, y+1)` and its centre is `(x + 0.5, y + 0.5)`), lies on
//!   the plane at distance 1 along `d` at
//!   `d + horizontal·(sx − w/2)/f + up'·(h/2 − sy)/f`.
//!
//! The ray starts at the eye with that point's unit direction.
//!
//! Edge rule: an `up` parallel to the direction (no horizontal defined) is
//! replaced by the world axis least aligned with the direction, so the
//! camera still works instead of producing NaN rays.

use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

/// Where a camera stands and what it sees.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// The eye.
    pub center: Point3<f64>,
    /// View direction (not necessarily unit).
    pub direction: Vector3<f64>,
    /// Up in the world (not necessarily unit nor perpendicular to the
    /// direction).
    pub up: Vector3<f64>,
    /// Vertical field of view in degrees.
    pub angle_degrees: f64,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// The camera frame, ready to turn image positions into rays.
#[derive(Debug, Clone)]
pub struct PinholeCamera {
    eye: Point3<f64>,
    direction: Vector3<f64>,
    horizontal: Vector3<f64>,
    up: Vector3<f64>,
    focal: f64,
    half_width: f64,
    half_height: f64,
    width: u32,
    height: u32,
}

impl PinholeCamera {
    /// The frame of `camera` (see the module docs for the formulas).
    pub fn new(camera: &Camera) -> PinholeCamera {
        let direction = if camera.direction.norm() > 0.0 {
            camera.direction.normalize()
        } else {
            -Vector3::z()
        };
        let mut horizontal = direction.cross(&camera.up);
        if horizontal.norm() <= 1e-12 * camera.up.norm() || !horizontal.norm().is_finite() {
            let a = direction.abs();
            let axis = if a.x <= a.y && a.x <= a.z {
                Vector3::x()
            } else if a.y <= a.z {
                Vector3::y()
            } else {
                Vector3::z()
            };
            horizontal = direction.cross(&axis);
        }
        let horizontal = horizontal.normalize();
        let up = horizontal.cross(&direction);
        let half_angle = camera.angle_degrees.to_radians() / 2.0;
        let focal = f64::from(camera.height) / (2.0 * half_angle.tan());
        PinholeCamera {
            eye: camera.center,
            direction,
            horizontal,
            up,
            focal,
            half_width: f64::from(camera.width) / 2.0,
            half_height: f64::from(camera.height) / 2.0,
            width: camera.width,
            height: camera.height,
        }
    }

    /// The ray through the image position `(sx, sy)` (pixels from the
    /// top-left corner), with a unit direction.
    #[inline]
    pub fn ray(&self, sx: f64, sy: f64) -> Ray {
        let dx = (sx - self.half_width) / self.focal;
        let dy = (self.half_height - sy) / self.focal;
        let dir = (self.direction + self.horizontal * dx + self.up * dy).normalize();
        Ray::new(self.eye, dir)
    }

    /// The rays through the pixel centres, row by row from the top (so
    /// consecutive rays are neighbours in one row).
    pub fn primary_rays(&self) -> Vec<Ray> {
        (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .map(|(x, y)| self.ray(f64::from(x) + 0.5, f64::from(y) + 0.5))
            .collect()
    }
}
