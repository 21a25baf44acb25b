//! The scene's lights, prepared once for sampling.
//!
//! - Delta lights (point and directional) are seen from a shading point `p`
//!   in one direction: `normalize(position − p)` at distance
//!   `|position − p|`, or `−normalize(direction)` at infinity. A point light
//!   exactly at `p`, or a directional light with a zero direction, lights
//!   nothing.
//! - An area light is the parallelogram `corner + a·e₁ + b·e₂`,
//!   `a, b ∈ [0, 1]`, with unit normal `n = normalize(e₁ × e₂)` and area
//!   `|e₁ × e₂|`. It emits its colour as radiance from both faces, and is
//!   sampled uniformly by area (density `1/area`). A ray meets its plane at
//!   `t = n·(corner − o)/(n·d)`; the point `q = o + t·d − corner` has
//!   coordinates `a = (q × e₂)·m / |m|²` and `b = (e₁ × q)·m / |m|²` with
//!   `m = e₁ × e₂`, and is on the light when both lie in `[0, 1]`.
//!   A degenerate parallelogram (zero area) is dropped.

use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

use crate::scene::{Color, Light, Scene};

/// A point or directional light.
#[derive(Debug, Clone)]
pub enum DeltaLight {
    /// `to_light` is the unit direction towards the light.
    Directional {
        to_light: Vector3<f64>,
        color: Color,
    },
    Point {
        position: Point3<f64>,
        color: Color,
    },
}

impl DeltaLight {
    /// The unit direction from `p` towards the light and the distance to
    /// it (infinite for a directional light); `None` when undefined.
    #[inline]
    pub fn toward(&self, p: &Point3<f64>) -> Option<(Vector3<f64>, f64)> {
        match self {
            DeltaLight::Directional { to_light, .. } => Some((*to_light, f64::INFINITY)),
            DeltaLight::Point { position, .. } => {
                let w = position - p;
                let d = w.norm();
                (d > 0.0 && d.is_finite()).then(|| (w / d, d))
            }
        }
    }

    /// The light's colour.
    #[inline]
    pub fn color(&self) -> &Color {
        match self {
            DeltaLight::Directional { color, .. } | DeltaLight::Point { color, .. } => color,
        }
    }
}

/// An `AreaLight` parallelogram with its precomputed frame.
#[derive(Debug, Clone)]
pub struct AreaLight {
    pub corner: Point3<f64>,
    pub edge1: Vector3<f64>,
    pub edge2: Vector3<f64>,
    /// Unit normal `normalize(e₁ × e₂)` (the light emits from both faces).
    pub normal: Vector3<f64>,
    pub area: f64,
    /// Emitted radiance.
    pub color: Color,
    /// `e₁ × e₂ / |e₁ × e₂|²`, for the in-plane coordinates of a hit.
    m_scaled: Vector3<f64>,
}

impl AreaLight {
    /// The light, or `None` if it has no area.
    pub fn new(
        corner: Point3<f64>,
        edge1: Vector3<f64>,
        edge2: Vector3<f64>,
        color: Color,
    ) -> Option<AreaLight> {
        let m = edge1.cross(&edge2);
        let area = m.norm();
        (area > 0.0 && area.is_finite()).then(|| AreaLight {
            corner,
            edge1,
            edge2,
            normal: m / area,
            area,
            color,
            m_scaled: m / (area * area),
        })
    }

    /// The point with coordinates `(a, b) ∈ [0, 1]²`.
    #[inline]
    pub fn point(&self, a: f64, b: f64) -> Point3<f64> {
        self.corner + self.edge1 * a + self.edge2 * b
    }

    /// The ray parameter at which `ray` crosses the light, if in
    /// `(t_min, t_max)`.
    #[inline]
    pub fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let denom = self.normal.dot(&ray.dir);
        if denom == 0.0 {
            return None;
        }
        let t = self.normal.dot(&(self.corner - ray.origin)) / denom;
        if !(t > t_min && t < t_max) {
            return None;
        }
        let q = ray.origin + ray.dir * t - self.corner;
        let a = q.cross(&self.edge2).dot(&self.m_scaled);
        let b = self.edge1.cross(&q).dot(&self.m_scaled);
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(t)
    }
}

/// All the scene's lights, split by kind.
#[derive(Debug, Clone, Default)]
pub struct Lights {
    pub delta: Vec<DeltaLight>,
    pub area: Vec<AreaLight>,
}

impl Lights {
    /// The lights of `scene` (degenerate ones dropped, see the module docs).
    pub fn of(scene: &Scene) -> Lights {
        let mut lights = Lights::default();
        for light in &scene.lights {
            match light {
                Light::Directional { direction, color } => {
                    let n = direction.norm();
                    if n > 0.0 && n.is_finite() {
                        lights.delta.push(DeltaLight::Directional {
                            to_light: -direction / n,
                            color: *color,
                        });
                    }
                }
                Light::Point { position, color } => lights.delta.push(DeltaLight::Point {
                    position: *position,
                    color: *color,
                }),
                Light::Area {
                    corner,
                    edge1,
                    edge2,
                    color,
                } => lights
                    .area
                    .extend(AreaLight::new(*corner, *edge1, *edge2, *color)),
            }
        }
        lights
    }

    /// The nearest area light on `ray` in `(t_min, t_max)`: its parameter
    /// and radiance.
    pub fn hit_area(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, Color)> {
        let mut best: Option<(f64, Color)> = None;
        for light in &self.area {
            let limit = best.map_or(t_max, |b| b.0);
            if let Some(t) = light.hit(ray, t_min, limit) {
                best = Some((t, light.color));
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> AreaLight {
        AreaLight::new(
            Point3::new(-1.0, 2.0, -1.0),
            Vector3::new(2.0, 0.0, 0.0),
            Vector3::new(0.0, 0.0, 2.0),
            Color::new(1.0, 1.0, 1.0),
        )
        .unwrap()
    }

    #[test]
    fn area_and_normal_come_from_the_edges() {
        let l = square();
        assert_eq!(l.area, 4.0);
        assert!((l.normal - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-15);
        assert_eq!(l.point(0.5, 0.5), Point3::new(0.0, 2.0, 0.0));
    }

    #[test]
    fn rays_hit_the_parallelogram_from_both_sides_and_miss_outside() {
        let l = square();
        let up = Ray::new(Point3::new(0.5, 0.0, 0.5), Vector3::y());
        assert_eq!(l.hit(&up, 0.0, f64::INFINITY), Some(2.0));
        assert_eq!(l.hit(&up, 0.0, 1.5), None);
        let down = Ray::new(Point3::new(0.5, 5.0, 0.5), -Vector3::y());
        assert_eq!(l.hit(&down, 0.0, f64::INFINITY), Some(3.0));
        let outside = Ray::new(Point3::new(1.5, 0.0, 0.5), Vector3::y());
        assert_eq!(l.hit(&outside, 0.0, f64::INFINITY), None);
        let parallel = Ray::new(Point3::new(0.0, 2.0, 0.0), Vector3::x());
        assert_eq!(l.hit(&parallel, 0.0, f64::INFINITY), None);
    }

    #[test]
    fn degenerate_lights_are_dropped_and_directions_normalized() {
        assert!(
            AreaLight::new(
                Point3::origin(),
                Vector3::x(),
                Vector3::x() * 2.0,
                Color::zeros()
            )
            .is_none()
        );
        let d = DeltaLight::Directional {
            to_light: Vector3::y(),
            color: Color::zeros(),
        };
        assert_eq!(d.toward(&Point3::origin()).unwrap().1, f64::INFINITY);
        let p = DeltaLight::Point {
            position: Point3::new(0.0, 3.0, 4.0),
            color: Color::zeros(),
        };
        let (l, dist) = p.toward(&Point3::origin()).unwrap();
        assert_eq!(dist, 5.0);
        assert!((l - Vector3::new(0.0, 0.6, 0.8)).norm() < 1e-15);
        assert!(p.toward(&Point3::new(0.0, 3.0, 4.0)).is_none());
    }
}
