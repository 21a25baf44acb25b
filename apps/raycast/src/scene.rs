//! What a scene file describes, after parsing: camera, lights, materials,
//! render settings and a flat list of objects placed in the world.
//!
//! The parser ([`crate::parse`]) flattens nested `Group`s and `Transform`s:
//! every object carries its material index and the composed object-to-world
//! matrix. The renderer never sees the file's nesting.

use std::sync::Arc;

use revolve::nalgebra::{Matrix4, Point3, Vector3};
use revolve::{
    Aabb, BSpline, BSplineSurface, Bezier, BezierPatches, BezierSurface, Intersect, Nurbs,
    NurbsSurface, Revolution,
};

/// Linear RGB, nominally in `[0, 1]` (light colours may exceed 1).
pub type Color = Vector3<f64>;

/// `PerspectiveCamera`: eye, view direction, up, vertical field of view.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    pub center: Point3<f64>,
    /// View direction (not necessarily unit).
    pub direction: Vector3<f64>,
    pub up: Vector3<f64>,
    /// Vertical field of view in degrees.
    pub angle_degrees: f64,
    pub width: u32,
    pub height: u32,
}

/// A light source.
#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    /// Light travelling along `direction` (the direction *to* the light is
    /// `−direction`), no fall-off.
    Directional {
        direction: Vector3<f64>,
        color: Color,
    },
    /// Light from `position`, no fall-off (as the course framework).
    Point { position: Point3<f64>, color: Color },
    /// A parallelogram `corner + a·edge1 + b·edge2`, `a, b ∈ [0, 1]`, emitting
    /// `color` (radiance) from both sides; gives soft shadows.
    Area {
        corner: Point3<f64>,
        edge1: Vector3<f64>,
        edge2: Vector3<f64>,
        color: Color,
    },
}

/// `PhongMaterial` / `Material` and the optional effect keywords. Missing
/// keywords are zero (and `refraction_index` is 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub diffuse: Color,
    pub specular: Color,
    pub shininess: f64,
    /// Mirror reflection weight.
    pub reflectivity: Color,
    /// Refraction weight (with Fresnel between reflection and refraction).
    pub transparency: Color,
    pub refraction_index: f64,
    /// Beer–Lambert attenuation per unit length inside the object.
    pub absorption: Color,
    /// Emitted radiance (the object is an area light).
    pub emission: Color,
    /// The diffuse colour from an image through the hit's `(u, v)`.
    pub texture: Option<Arc<Texture>>,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            diffuse: Color::zeros(),
            specular: Color::zeros(),
            shininess: 0.0,
            reflectivity: Color::zeros(),
            transparency: Color::zeros(),
            refraction_index: 1.0,
            absorption: Color::zeros(),
            emission: Color::zeros(),
            texture: None,
        }
    }
}

/// An RGB image in linear `[0, 1]`, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Color>,
}

/// A triangle mesh read from an OBJ file (positions and triangles; polygons
/// are split into fans).
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleMesh {
    pub vertices: Vec<Point3<f64>>,
    pub triangles: Vec<[u32; 3]>,
}

/// The profile of a `RevSurface`, revolved about the local `y` axis with
/// revolve's exact intersector.
#[derive(Debug, Clone)]
pub enum RevolutionBody {
    Bezier(Revolution<Bezier<2>>),
    BSpline(Revolution<BSpline<2>>),
    Nurbs(Revolution<Nurbs<2>>),
}

/// A tensor-product surface (`BezierSurface`, `BsplineSurface`) or a model
/// of bicubic patches (`BezierPatches`), intersected by revolve's certified
/// patch search.
#[derive(Debug, Clone)]
pub enum SurfaceBody {
    Bezier(BezierSurface),
    BSpline(BSplineSurface),
    /// A `BsplineSurface` or `BezierSurface` with a weighted control point.
    Nurbs(NurbsSurface),
    /// The patches of a `BezierPatches` file, in file order, behind
    /// revolve's hierarchy.
    Patches(BezierPatches),
}

impl SurfaceBody {
    /// The body as revolve's ray target.
    pub fn target(&self) -> &dyn Intersect {
        match self {
            SurfaceBody::Bezier(s) => s,
            SurfaceBody::BSpline(s) => s,
            SurfaceBody::Nurbs(s) => s,
            SurfaceBody::Patches(model) => model,
        }
    }

    /// revolve's box around everything the body can be hit at.
    pub fn bounds(&self) -> Aabb {
        self.target().bounds()
    }
}

/// A curve drawn directly in a group: rendered as a thin tube along
/// `points` (its flattening).
#[derive(Debug, Clone, PartialEq)]
pub struct Tube {
    pub points: Vec<Point3<f64>>,
    pub radius: f64,
}

/// The geometry of one object, in its own frame.
#[derive(Debug, Clone)]
pub enum Shape {
    Sphere {
        center: Point3<f64>,
        radius: f64,
    },
    /// Points `p` with `normal · p = offset`.
    Plane {
        normal: Vector3<f64>,
        offset: f64,
    },
    Triangle {
        vertices: [Point3<f64>; 3],
    },
    Mesh(Arc<TriangleMesh>),
    Box {
        min: Point3<f64>,
        max: Point3<f64>,
    },
    Disk {
        center: Point3<f64>,
        normal: Vector3<f64>,
        radius: f64,
    },
    Ring {
        center: Point3<f64>,
        normal: Vector3<f64>,
        inner: f64,
        outer: f64,
    },
    Rectangle {
        corner: Point3<f64>,
        edge1: Vector3<f64>,
        edge2: Vector3<f64>,
    },
    Revolution(Arc<RevolutionBody>),
    Tube(Arc<Tube>),
    Surface(Arc<SurfaceBody>),
}

/// One object placed in the world.
#[derive(Debug, Clone)]
pub struct Object {
    pub shape: Shape,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// Object-to-world matrix (the composition of the enclosing
    /// `Transform`s in the order written); `None` for the identity.
    pub transform: Option<Matrix4<f64>>,
}

/// Which light-transport algorithm renders the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integrator {
    /// Primary rays, Phong shading and the effects the scene calls for.
    Whitted,
    /// Monte Carlo path tracing (Lambertian diffuse, next-event estimation,
    /// Russian roulette).
    Path,
}

/// Tone mapping applied before writing (path tracing only).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToneMap {
    /// Clamp to `[0, 1]`, ×255, no gamma (the course framework's output).
    Clamp,
    /// Reinhard `c/(1 + c)` then sRGB gamma.
    Reinhard,
}

/// The optional `Render { ... }` block. `None` means "not given": the
/// renderer then decides from the scene's contents.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RenderSettings {
    /// `samples N` per pixel.
    pub samples: Option<u32>,
    /// `maxDepth N`: bounces of reflection/refraction or path length.
    pub max_depth: Option<u32>,
    /// `shadows true|false`.
    pub shadows: Option<bool>,
    /// `integrator whitted|path`.
    pub integrator: Option<Integrator>,
    /// `toneMap clamp|reinhard`.
    pub tone_map: Option<ToneMap>,
}

/// A whole scene.
#[derive(Debug, Clone)]
pub struct Scene {
    pub camera: Camera,
    pub lights: Vec<Light>,
    pub background: Color,
    pub materials: Vec<Material>,
    pub objects: Vec<Object>,
    pub render: RenderSettings,
}
