//! The scene format's block keywords: the objects and the others. The
//! parsers dispatch on them and the cursor names them when one stands
//! where it cannot.

/// The object keywords.
pub(super) const OBJECTS: &[&str] = &[
    "Group",
    "Transform",
    "Sphere",
    "Plane",
    "Triangle",
    "TriangleMesh",
    "Box",
    "Disk",
    "Ring",
    "Rectangle",
    "RevSurface",
    "BezierCurve",
    "BsplineCurve",
    "NurbsCurve",
    "BezierSurface",
    "BsplineSurface",
    "BezierPatches",
    "RuledSurface",
    "ExtrudedSurface",
    "LoftedSurface",
];

/// The block keywords of the format other than the objects
/// ([`OBJECTS`]), to explain a misplaced one.
pub(super) const BLOCK_KEYWORDS: &[&str] = &[
    "PerspectiveCamera",
    "Lights",
    "DirectionalLight",
    "PointLight",
    "AreaLight",
    "Background",
    "Materials",
    "PhongMaterial",
    "Material",
    "Render",
];
