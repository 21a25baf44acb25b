//! The pinhole camera of the course framework.
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

use crate::scene::Camera;

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

    /// Where the world point `p` appears in the image, in pixels from the
    /// top-left corner; `None` behind the eye. (The inverse of [`ray`].)
    ///
    /// [`ray`]: Self::ray
    #[cfg(test)]
    pub fn project(&self, p: &Point3<f64>) -> Option<(f64, f64)> {
        let v = p - self.eye;
        let depth = v.dot(&self.direction);
        if depth <= 0.0 {
            return None;
        }
        let x = v.dot(&self.horizontal) / depth * self.focal + self.half_width;
        let y = self.half_height - v.dot(&self.up) / depth * self.focal;
        Some((x, y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(width: u32, height: u32) -> Camera {
        Camera {
            center: Point3::new(0.0, 0.0, 10.0),
            direction: Vector3::new(0.0, 0.0, -2.0),
            up: Vector3::new(0.0, 1.0, 0.0),
            angle_degrees: 90.0,
            width,
            height,
        }
    }

    #[test]
    fn centre_of_an_odd_image_looks_along_the_direction() {
        let c = PinholeCamera::new(&camera(33, 33));
        let r = c.ray(16.5, 16.5);
        assert!((r.dir - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-15);
        assert_eq!(r.origin, Point3::new(0.0, 0.0, 10.0));
    }

    #[test]
    fn row_zero_is_at_the_top_and_column_zero_on_the_left() {
        let c = PinholeCamera::new(&camera(40, 20));
        let r = c.ray(0.5, 0.5);
        assert!(r.dir.x < 0.0 && r.dir.y > 0.0 && r.dir.z < 0.0);
        let r = c.ray(39.5, 19.5);
        assert!(r.dir.x > 0.0 && r.dir.y < 0.0);
    }

    #[test]
    fn the_vertical_field_of_view_spans_the_image_height() {
        // 90° vertical: the top edge of the image is at 45° above the axis.
        let c = PinholeCamera::new(&camera(64, 32));
        let r = c.ray(32.0, 0.0);
        assert!((r.dir.y - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-12);
        // Square pixels: the left edge is at atan(64/32) = atan(2).
        let r = c.ray(0.0, 16.0);
        assert!((-r.dir.x / -r.dir.z - 2.0).abs() < 1e-12);
    }

    #[test]
    fn projection_inverts_the_ray() {
        let c = PinholeCamera::new(&Camera {
            center: Point3::new(1.0, 2.0, 3.0),
            direction: Vector3::new(-0.3, -0.2, -1.0),
            up: Vector3::new(0.1, 1.0, 0.0),
            angle_degrees: 40.0,
            width: 50,
            height: 30,
        });
        let r = c.ray(12.25, 7.75);
        let (x, y) = c.project(&r.at(4.0)).unwrap();
        assert!((x - 12.25).abs() < 1e-9 && (y - 7.75).abs() < 1e-9);
    }

    #[test]
    fn an_up_parallel_to_the_direction_still_gives_finite_rays() {
        let mut cam = camera(8, 8);
        cam.up = Vector3::new(0.0, 0.0, 1.0);
        let r = PinholeCamera::new(&cam).ray(0.0, 0.0);
        assert!(r.dir.iter().all(|v| v.is_finite()));
    }
}
