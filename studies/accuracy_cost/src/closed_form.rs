//! The reference for the study's rational shapes: the NURBS sphere and
//! torus against the exact sphere and torus, their ray equations (the
//! quadratic and the quartic) with exact coefficients from the `f64`
//! inputs, solved by Sturm sequences in integer arithmetic and rounded
//! correctly (`revolve_testkit::closed_forms`, shared with
//! `tests/revolution/rational_revolution.rs`; its
//! [`Certifier`](crate::reference::Certifier) is there
//! too).
//!
//! The NURBS profiles (quarter arcs with the weight `√2/2` rounded to
//! `f64`) are the exact circles to about `1e-16` of their size, so errors
//! against these references have that floor. Every ray with a finite
//! origin and a non-zero direction is certified (tangent contacts too).

pub use crate::common::closed_forms::ClosedForm;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::Certifier;
    use revolve::Ray;
    use revolve::nalgebra::{Point3, Vector3};

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(Point3::from(o), Vector3::from(d))
    }

    #[test]
    fn closed_forms_answer_simple_rays() {
        let sphere = ClosedForm::Sphere { radius: 1.5 };
        let up = ray([0.0, -4.0, 0.0], [0.0, 2.0, 0.0]);
        assert_eq!(sphere.certify(&up, 0.0, f64::INFINITY), Some(Some(1.25)));
        assert_eq!(sphere.certify(&up, 1.25, f64::INFINITY), Some(Some(2.75)));
        assert_eq!(sphere.certify(&up, 0.0, 1.25), Some(None));
        let torus = ClosedForm::Torus {
            major: 1.0,
            minor: 0.25,
        };
        // Through the hole, and across the tube: t = 3 − 1.25 first.
        assert_eq!(torus.certify(&up, -9.0, 9.0), Some(None));
        let across = ray([-3.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        assert_eq!(torus.certify(&across, 0.0, 9.0), Some(Some(1.75)));
        assert_eq!(torus.certify(&across, 1.75, 9.0), Some(Some(2.25)));
        // Nothing certain for a non-finite ray.
        let bad = ray([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0]);
        assert_eq!(torus.certify(&bad, 0.0, 9.0), None);
    }
}
