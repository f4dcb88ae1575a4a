// Ripple's subtype and parameter tables for anariGetObjectSubtypes / ObjectInfo / ParameterInfo, and its
// extension list (see Introspection.h). They describe what the object classes read in commit().
#include "anari/device/Introspection.h"

#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>
#include <vector>

namespace ripple::device {
namespace {

// Default values, in the parameter's own type.
constexpr float kZero = 0.0f;
constexpr float kHalf = 0.5f;
constexpr float kOne = 1.0f;
constexpr float kIor = 1.5f;
constexpr float kFovy = 1.0471975512f;  // pi / 3
constexpr float kPiValue = 3.14159265359f;
constexpr float kFalloff = 0.1f;
constexpr float kGrey[3] = {0.8f, 0.8f, 0.8f};
constexpr float kWhite[3] = {1.0f, 1.0f, 1.0f};
constexpr float kBlack[3] = {0.0f, 0.0f, 0.0f};
constexpr float kOpaqueBlack[4] = {0.0f, 0.0f, 0.0f, 1.0f};
constexpr float kOrigin[3] = {0.0f, 0.0f, 0.0f};
constexpr float kMinusZ[3] = {0.0f, 0.0f, -1.0f};
constexpr float kPlusY[3] = {0.0f, 1.0f, 0.0f};
constexpr float kPlusX[3] = {1.0f, 0.0f, 0.0f};
constexpr float kPlusZ[3] = {0.0f, 0.0f, 1.0f};
constexpr float kUnitRegion[4] = {0.0f, 0.0f, 1.0f, 1.0f};
constexpr float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
constexpr float kNoOffset[4] = {0.0f, 0.0f, 0.0f, 0.0f};
constexpr int32_t kTrue = 1;
constexpr int32_t kFalse = 0;
constexpr int32_t kOneSample = 1;
constexpr int32_t kPathLength = 5;
constexpr uint32_t kSeed = 0;

constexpr const char* kCaps[] = {"none", "first", "second", "both", nullptr};
constexpr const char* kLayouts[] = {"equirectangular", nullptr};
constexpr const char* kAlphaModes[] = {"opaque", "blend", "mask", nullptr};
constexpr const char* kFilters[] = {"nearest", "linear", nullptr};
constexpr const char* kWrapModes[] = {"clampToEdge", "repeat", "mirrorRepeat", nullptr};
constexpr const char* kSides[] = {"front", "back", "both", nullptr};
constexpr const char* kTraversals[] = {"auto", "software", "rayQuery", nullptr};
constexpr const char* kExchanges[] = {"bounds", "ring", nullptr};
constexpr const char* kAttributes[] = {"attribute0", "attribute1", "attribute2", "attribute3", "color",
                                       "primitiveId", "worldPosition", "worldNormal", nullptr};

struct Param {
    const char* name;
    ANARIDataType type;
    const char* description;
    const void* defaultValue = nullptr;  // of `type`; for ANARI_STRING the string itself
    const char* const* values = nullptr; // accepted strings, nullptr-terminated
    bool required = false;
};

struct Entry {
    ANARIDataType type;
    const char* subtype;  // "" for types without subtypes
    const char* description;
    std::vector<Param> parameters;
};

std::vector<Param> joined(std::initializer_list<std::vector<Param>> parts) {
    std::vector<Param> all;
    for (const std::vector<Param>& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
}

const std::vector<Param> kName = {{"name", ANARI_STRING, "optional object name"}};

const std::vector<Param> kGeometryCommon = joined({kName, {
    {"vertex.position", ANARI_ARRAY1D, "vertex positions (FLOAT32_VEC3)", nullptr, nullptr, true},
    {"vertex.color", ANARI_ARRAY1D, "per-vertex colour (any numeric or sRGB type, up to 4 components)"},
    {"primitive.color", ANARI_ARRAY1D, "per-primitive colour"},
    {"color", ANARI_FLOAT32_VEC4, "uniform colour, when no per-vertex or per-primitive colour is given"},
    {"vertex.attribute0", ANARI_ARRAY1D, "per-vertex values samplers and materials read (up to 4 components); "
                                         "on meshes also the texture coordinates normal maps take their frame from"},
    {"vertex.attribute1", ANARI_ARRAY1D, "per-vertex values samplers and materials read (up to 4 components)"},
    {"vertex.attribute2", ANARI_ARRAY1D, "per-vertex values samplers and materials read (up to 4 components)"},
    {"vertex.attribute3", ANARI_ARRAY1D, "per-vertex values samplers and materials read (up to 4 components)"},
    {"primitive.attribute0", ANARI_ARRAY1D, "per-primitive attribute0, when vertex.attribute0 is unset"},
    {"primitive.attribute1", ANARI_ARRAY1D, "per-primitive attribute1, when vertex.attribute1 is unset"},
    {"primitive.attribute2", ANARI_ARRAY1D, "per-primitive attribute2, when vertex.attribute2 is unset"},
    {"primitive.attribute3", ANARI_ARRAY1D, "per-primitive attribute3, when vertex.attribute3 is unset"},
    {"attribute0", ANARI_FLOAT32_VEC4, "uniform attribute0, when neither array is given"},
    {"attribute1", ANARI_FLOAT32_VEC4, "uniform attribute1, when neither array is given"},
    {"attribute2", ANARI_FLOAT32_VEC4, "uniform attribute2, when neither array is given"},
    {"attribute3", ANARI_FLOAT32_VEC4, "uniform attribute3, when neither array is given"},
}});

const std::vector<Param> kMeshExtras = {
    {"vertex.normal", ANARI_ARRAY1D, "shading normals (FLOAT32_VEC3)"},
    {"vertex.tangent", ANARI_ARRAY1D, "normal maps' tangent (FLOAT32_VEC3, or VEC4 with w the handedness); "
                                      "unset: from vertex.attribute0"},
};

const std::vector<Param> kViewCommon = joined({kName, {
    {"position", ANARI_FLOAT32_VEC3, "camera position", kOrigin},
    {"direction", ANARI_FLOAT32_VEC3, "main viewing direction", kMinusZ},
    {"up", ANARI_FLOAT32_VEC3, "up direction", kPlusY},
    {"imageRegion", ANARI_FLOAT32_BOX2, "region of the screen mapped to the frame", kUnitRegion},
    {"aspect", ANARI_FLOAT32, "width / height; the frame's when unset"},
}});

const std::vector<Param> kLightCommon = joined({kName, {{"color", ANARI_FLOAT32_VEC3, "colour of the light", kWhite}}});

const std::vector<Param> kAlpha = {
    {"alphaMode", ANARI_STRING, "read, not used yet: surfaces render opaque", "opaque", kAlphaModes},
    {"alphaCutoff", ANARI_FLOAT32, "read, not used yet", &kHalf},
};

const std::vector<Entry>& table() {
    static const std::vector<Entry> entries = {
        {ANARI_DEVICE, "default", "Ripple: a wavefront path tracer on Vulkan compute, data-parallel over MPI",
         {
             {"statusCallback", ANARI_STATUS_CALLBACK, "receives the device's errors, warnings and messages"},
             {"statusCallbackUserData", ANARI_VOID_POINTER, "handed to statusCallback"},
             {"traversal", ANARI_STRING,
              "ray traversal back-end: auto (ray queries on GPUs that have them, else software), software (Ripple's "
              "BVH kernels) or rayQuery (VK_KHR_ray_query); RIPPLE_TRAVERSAL sets the default",
              "auto", kTraversals},
             {"rayExchange", ANARI_STRING,
              "how rays cross ranks: bounds (only to the ranks whose boxes a ray enters) or ring (every rank)",
              "bounds", kExchanges},
             {"mpiCommunicator", ANARI_VOID_POINTER, "address of the MPI_Comm the ranks render over (default: MPI_COMM_WORLD)"},
             {"vulkanDevice", ANARI_STRING,
              "the Vulkan device to render with: an index or a substring of its name (device property "
              "ripple.vulkanDevices lists them); unset: RIPPLE_VK_DEVICE, else the best kind of device, one per "
              "rank of a node in turn; set before the first render"},
             {"discreteMemory", ANARI_BOOL,
              "treat GPU memory as the host cannot map it: every upload and download goes through staging buffers, "
              "as on a discrete GPU (a test of that path on CPU devices); set before the first render; "
              "RIPPLE_VK_DISCRETE_MEMORY=1 sets the default",
              &kFalse},
         }},
        {ANARI_GEOMETRY, "triangle", "triangle mesh, indexed (primitive.index UINT32_VEC3) or not",
         joined({kGeometryCommon, kMeshExtras, {{"primitive.index", ANARI_ARRAY1D, "vertex indices (UINT32_VEC3)"}}})},
        {ANARI_GEOMETRY, "quad", "quad mesh, rendered as two triangles per quad",
         joined({kGeometryCommon, kMeshExtras, {{"primitive.index", ANARI_ARRAY1D, "vertex indices (UINT32_VEC4)"}}})},
        {ANARI_GEOMETRY, "sphere", "spheres centred on the vertices",
         joined({kGeometryCommon, {
             {"primitive.index", ANARI_ARRAY1D, "vertices to place spheres on (UINT32)"},
             {"vertex.radius", ANARI_ARRAY1D, "per-sphere radius (FLOAT32)"},
             {"radius", ANARI_FLOAT32, "radius of all spheres when vertex.radius is unset", &kOne},
         }})},
        {ANARI_GEOMETRY, "cylinder", "cylinders between vertex pairs",
         joined({kGeometryCommon, {
             {"primitive.index", ANARI_ARRAY1D, "vertex pairs (UINT32_VEC2)"},
             {"primitive.radius", ANARI_ARRAY1D, "per-cylinder radius (FLOAT32)"},
             {"radius", ANARI_FLOAT32, "radius of all cylinders when primitive.radius is unset", &kOne},
             {"caps", ANARI_STRING, "which ends a flat disk closes", "none", kCaps},
             {"vertex.cap", ANARI_ARRAY1D, "nonzero: a flat disk closes the segments ending at this vertex (UINT8)"},
         }})},
        {ANARI_GEOMETRY, "cone", "cone frusta between vertex pairs, a radius at each vertex",
         joined({kGeometryCommon, {
             {"primitive.index", ANARI_ARRAY1D, "vertex pairs (UINT32_VEC2)"},
             {"vertex.radius", ANARI_ARRAY1D, "radius at each vertex (FLOAT32)", nullptr, nullptr, true},
             {"caps", ANARI_STRING, "which ends a flat disk closes", "none", kCaps},
             {"vertex.cap", ANARI_ARRAY1D, "nonzero: a flat disk closes the segments ending at this vertex (UINT8)"},
         }})},
        {ANARI_GEOMETRY, "curve", "round linear segments from each indexed vertex to the next",
         joined({kGeometryCommon, {
             {"primitive.index", ANARI_ARRAY1D, "first vertex of each segment (UINT32); one polyline when unset"},
             {"vertex.radius", ANARI_ARRAY1D, "radius at each vertex (FLOAT32)"},
             {"radius", ANARI_FLOAT32, "radius of all vertices when vertex.radius is unset", &kOne},
         }})},
        {ANARI_GEOMETRY, "isosurface", "surfaces of equal value of a structuredRegular field, traced exactly",
         joined({kName, {
             {"field", ANARI_SPATIAL_FIELD, "the field (its trilinear interpolant)", nullptr, nullptr, true},
             {"isovalue", ANARI_FLOAT32, "the value of the one surface", nullptr, nullptr, true},
             {"isovalue", ANARI_ARRAY1D, "values of several surfaces (FLOAT32)"},
             {"primitive.color", ANARI_ARRAY1D, "colour per isovalue"},
             {"color", ANARI_FLOAT32_VEC4, "uniform colour, when primitive.color is unset"},
             {"primitive.attribute0", ANARI_ARRAY1D, "attribute0 per isovalue"},
             {"primitive.attribute1", ANARI_ARRAY1D, "attribute1 per isovalue"},
             {"primitive.attribute2", ANARI_ARRAY1D, "attribute2 per isovalue"},
             {"primitive.attribute3", ANARI_ARRAY1D, "attribute3 per isovalue"},
             {"attribute0", ANARI_FLOAT32_VEC4, "uniform attribute0, when primitive.attribute0 is unset"},
             {"attribute1", ANARI_FLOAT32_VEC4, "uniform attribute1, when primitive.attribute1 is unset"},
             {"attribute2", ANARI_FLOAT32_VEC4, "uniform attribute2, when primitive.attribute2 is unset"},
             {"attribute3", ANARI_FLOAT32_VEC4, "uniform attribute3, when primitive.attribute3 is unset"},
         }})},
        {ANARI_MATERIAL, "matte", "Lambertian diffuse",
         joined({kName, kAlpha, {
             {"color", ANARI_FLOAT32_VEC3, "diffuse colour", kGrey},
             {"color", ANARI_SAMPLER, "diffuse colour from an image1D/image2D sampler"},
             {"color", ANARI_STRING, "diffuse colour from a surface attribute", "color", kAttributes},
             {"opacity", ANARI_FLOAT32, "opacity", &kOne},
             {"opacity", ANARI_SAMPLER, "opacity from a sampler's first component"},
             {"opacity", ANARI_STRING, "opacity from a surface attribute's first component", "attribute0", kAttributes},
         }})},
        {ANARI_MATERIAL, "physicallyBased", "glTF metallic-roughness",
         joined({kName, kAlpha, {
             {"baseColor", ANARI_FLOAT32_VEC3, "base colour", kWhite},
             {"baseColor", ANARI_SAMPLER, "base colour from an image1D/image2D sampler"},
             {"baseColor", ANARI_STRING, "base colour from a surface attribute", "color", kAttributes},
             {"opacity", ANARI_FLOAT32, "opacity", &kOne},
             {"opacity", ANARI_SAMPLER, "opacity from a sampler's first component"},
             {"opacity", ANARI_STRING, "opacity from a surface attribute's first component", "attribute0", kAttributes},
             {"metallic", ANARI_FLOAT32, "metalness", &kOne},
             {"metallic", ANARI_SAMPLER, "metalness from a sampler's first component"},
             {"metallic", ANARI_STRING, "metalness from a surface attribute's first component", "attribute0", kAttributes},
             {"roughness", ANARI_FLOAT32, "roughness", &kOne},
             {"roughness", ANARI_SAMPLER, "roughness from a sampler's first component"},
             {"roughness", ANARI_STRING, "roughness from a surface attribute's first component", "attribute0", kAttributes},
             {"emissive", ANARI_FLOAT32_VEC3, "emitted radiance", kBlack},
             {"emissive", ANARI_SAMPLER, "emitted radiance from a sampler's rgb"},
             {"emissive", ANARI_STRING, "emitted radiance from a surface attribute's rgb", "attribute0", kAttributes},
             {"normal", ANARI_SAMPLER, "tangent-space normal map (rgb in [0,1]; needs texture coordinates)"},
             {"ior", ANARI_FLOAT32, "index of refraction", &kIor},
         }})},
        {ANARI_SAMPLER, "image1D", "1D image texture (a colour map)",
         joined({kName, {
             {"image", ANARI_ARRAY1D, "texels (UFIXED8_VEC4, UFIXED8_RGBA_SRGB, FLOAT32_VEC4...)", nullptr, nullptr,
              true},
             {"inAttribute", ANARI_STRING, "texture coordinate attribute (first component used)", "attribute0",
              kAttributes},
             {"filter", ANARI_STRING, "texel filter", "linear", kFilters},
             {"wrapMode", ANARI_STRING, "wrap mode", "clampToEdge", kWrapModes},
             {"inTransform", ANARI_FLOAT32_MAT4, "applied to the attribute before lookup", kIdentity},
             {"inOffset", ANARI_FLOAT32_VEC4, "added after inTransform", kNoOffset},
             {"outTransform", ANARI_FLOAT32_MAT4, "applied to the texel", kIdentity},
             {"outOffset", ANARI_FLOAT32_VEC4, "added after outTransform", kNoOffset},
         }})},
        {ANARI_SAMPLER, "image2D", "2D image texture",
         joined({kName, {
             {"image", ANARI_ARRAY2D, "texels (UFIXED8_VEC4, UFIXED8_RGBA_SRGB, FLOAT32_VEC4...)", nullptr, nullptr,
              true},
             {"inAttribute", ANARI_STRING, "texture coordinate attribute", "attribute0", kAttributes},
             {"filter", ANARI_STRING, "texel filter", "linear", kFilters},
             {"wrapMode1", ANARI_STRING, "wrap mode along u", "clampToEdge", kWrapModes},
             {"wrapMode2", ANARI_STRING, "wrap mode along v", "clampToEdge", kWrapModes},
             {"inTransform", ANARI_FLOAT32_MAT4, "applied to the attribute before lookup", kIdentity},
             {"inOffset", ANARI_FLOAT32_VEC4, "added after inTransform", kNoOffset},
             {"outTransform", ANARI_FLOAT32_MAT4, "applied to the texel", kIdentity},
             {"outOffset", ANARI_FLOAT32_VEC4, "added after outTransform", kNoOffset},
         }})},
        {ANARI_SAMPLER, "image3D", "3D image texture (trilinear or nearest)",
         joined({kName, {
             {"image", ANARI_ARRAY3D, "texels (UFIXED8_VEC4, FLOAT32_VEC4...)", nullptr, nullptr, true},
             {"inAttribute", ANARI_STRING, "texture coordinate attribute", "attribute0", kAttributes},
             {"filter", ANARI_STRING, "texel filter", "linear", kFilters},
             {"wrapMode1", ANARI_STRING, "wrap mode along u", "clampToEdge", kWrapModes},
             {"wrapMode2", ANARI_STRING, "wrap mode along v", "clampToEdge", kWrapModes},
             {"wrapMode3", ANARI_STRING, "wrap mode along w", "clampToEdge", kWrapModes},
             {"inTransform", ANARI_FLOAT32_MAT4, "applied to the attribute before lookup", kIdentity},
             {"inOffset", ANARI_FLOAT32_VEC4, "added after inTransform", kNoOffset},
             {"outTransform", ANARI_FLOAT32_MAT4, "applied to the texel", kIdentity},
             {"outOffset", ANARI_FLOAT32_VEC4, "added after outTransform", kNoOffset},
         }})},
        {ANARI_SAMPLER, "transform", "an attribute, transformed (no image)",
         joined({kName, {
             {"inAttribute", ANARI_STRING, "attribute read", "attribute0", kAttributes},
             {"outTransform", ANARI_FLOAT32_MAT4, "applied to the attribute", kIdentity},
             {"outOffset", ANARI_FLOAT32_VEC4, "added after outTransform", kNoOffset},
         }})},
        {ANARI_SAMPLER, "primitive", "one array entry per primitive",
         joined({kName, {
             {"array", ANARI_ARRAY1D, "values (FLOAT32_VEC4...), indexed by primitive id", nullptr, nullptr, true},
             {"inOffset", ANARI_UINT64, "added to the primitive id", nullptr},
         }})},
        {ANARI_LIGHT, "directional", "parallel light",
         joined({kLightCommon, {
             {"direction", ANARI_FLOAT32_VEC3, "direction the light travels", kMinusZ},
             {"irradiance", ANARI_FLOAT32, "W/m^2 on a surface facing the light", &kOne},
             {"angularDiameter", ANARI_FLOAT32, "apparent size of the light in radians, 0 to pi (0: a delta light)", &kZero},
         }})},
        {ANARI_LIGHT, "point", "isotropic point light",
         joined({kLightCommon, {
             {"position", ANARI_FLOAT32_VEC3, "position", kOrigin},
             {"intensity", ANARI_FLOAT32, "W/sr", &kOne},
             {"power", ANARI_FLOAT32, "W, used when intensity is unset"},
         }})},
        {ANARI_LIGHT, "quad", "emitting parallelogram",
         joined({kLightCommon, {
             {"position", ANARI_FLOAT32_VEC3, "a corner", kOrigin},
             {"edge1", ANARI_FLOAT32_VEC3, "first edge", kPlusX},
             {"edge2", ANARI_FLOAT32_VEC3, "second edge", kPlusY},
             {"intensity", ANARI_FLOAT32, "W/sr along the normal", &kOne},
             {"power", ANARI_FLOAT32, "W, used when radiance is unset"},
             {"radiance", ANARI_FLOAT32, "W/sr/m^2, takes precedence"},
             {"side", ANARI_STRING, "emitting side(s); front is along edge1 x edge2", "front", kSides},
         }})},
        {ANARI_LIGHT, "spot", "cone of light from a point",
         joined({kLightCommon, {
             {"position", ANARI_FLOAT32_VEC3, "position", kOrigin},
             {"direction", ANARI_FLOAT32_VEC3, "axis of the cone", kMinusZ},
             {"openingAngle", ANARI_FLOAT32, "full angle of the cone, radians", &kPiValue},
             {"falloffAngle", ANARI_FLOAT32, "angle of the fade at the cone's edge, radians", &kFalloff},
             {"intensity", ANARI_FLOAT32, "W/sr", &kOne},
             {"power", ANARI_FLOAT32, "W, used when intensity is unset"},
         }})},
        {ANARI_LIGHT, "ring", "emitting annulus with a spot profile",
         joined({kLightCommon, {
             {"position", ANARI_FLOAT32_VEC3, "centre", kOrigin},
             {"direction", ANARI_FLOAT32_VEC3, "axis the ring faces", kMinusZ},
             {"openingAngle", ANARI_FLOAT32, "full angle of the cone, radians", &kPiValue},
             {"falloffAngle", ANARI_FLOAT32, "angle of the fade at the cone's edge, radians", &kFalloff},
             {"radius", ANARI_FLOAT32, "outer radius", &kZero},
             {"innerRadius", ANARI_FLOAT32, "inner radius", &kZero},
             {"intensity", ANARI_FLOAT32, "W/sr along the axis", &kOne},
             {"power", ANARI_FLOAT32, "W, used when intensity is unset"},
             {"radiance", ANARI_FLOAT32, "W/sr/m^2, takes precedence"},
             {"c0", ANARI_FLOAT32_VEC3, "photometric C0 direction (unused: no intensityDistribution)"},
         }})},
        {ANARI_LIGHT, "hdri", "equirectangular environment, importance-sampled",
         joined({kLightCommon, {
             {"radiance", ANARI_ARRAY2D, "W/sr/m^2 per texel (FLOAT32_VEC3 or VEC4)", nullptr, nullptr, true},
             {"direction", ANARI_FLOAT32_VEC3, "direction the image centre is seen in", kPlusX},
             {"up", ANARI_FLOAT32_VEC3, "direction of the image's top row", kPlusZ},
             {"scale", ANARI_FLOAT32, "factor on the radiance", &kOne},
             {"layout", ANARI_STRING, "pixel layout (only equirectangular)", "equirectangular", kLayouts},
         }})},
        {ANARI_CAMERA, "perspective", "pinhole camera",
         joined({kViewCommon, {
             {"fovy", ANARI_FLOAT32, "vertical field of view in radians", &kFovy},
             {"apertureRadius", ANARI_FLOAT32, "lens radius for depth of field; 0 is a pinhole", &kZero},
             {"focusDistance", ANARI_FLOAT32, "distance of the plane in focus", &kOne},
             {"near", ANARI_FLOAT32, "near clip plane's distance along direction", &kZero},
             {"far", ANARI_FLOAT32, "far clip plane's distance along direction; unset: none"},
         }})},
        {ANARI_CAMERA, "orthographic", "parallel projection",
         joined({kViewCommon, {{"height", ANARI_FLOAT32, "height of the image plane in world units", &kOne},
                               {"near", ANARI_FLOAT32, "near clip plane's distance along direction", &kZero},
                               {"far", ANARI_FLOAT32, "far clip plane's distance along direction; unset: none"}}})},
        {ANARI_CAMERA, "omnidirectional", "every direction around the position, equirectangular",
         joined({kViewCommon, {{"layout", ANARI_STRING, "pixel layout (only equirectangular)", "equirectangular", kLayouts}}})},
        {ANARI_INSTANCE, "transform", "a group placed by an affine transform",
         joined({kName, {
             {"group", ANARI_GROUP, "the group placed", nullptr, nullptr, true},
             {"transform", ANARI_FLOAT32_MAT4, "object to world, column-major", kIdentity},
             {"id", ANARI_UINT32, "instance id for the instanceId channel; ~0u when unset"},
             {"color", ANARI_FLOAT32_VEC4, "uniform colour; replaces the geometries' colour on this instance"},
             {"attribute0", ANARI_FLOAT32_VEC4, "uniform attribute0; replaces the geometries' on this instance"},
             {"attribute1", ANARI_FLOAT32_VEC4, "uniform attribute1; replaces the geometries' on this instance"},
             {"attribute2", ANARI_FLOAT32_VEC4, "uniform attribute2; replaces the geometries' on this instance"},
             {"attribute3", ANARI_FLOAT32_VEC4, "uniform attribute3; replaces the geometries' on this instance"},
         }})},
        {ANARI_RENDERER, "default", "wavefront path tracer",
         joined({kName, {
             {"background", ANARI_FLOAT32_VEC4, "colour seen by camera rays that miss", kOpaqueBlack},
             {"ambientColor", ANARI_FLOAT32_VEC3, "colour of the uniform environment light", kWhite},
             {"ambientRadiance", ANARI_FLOAT32, "radiance of the uniform environment light", &kZero},
             {"pixelSamples", ANARI_INT32, "samples per pixel added by each anariRenderFrame", &kOneSample},
             {"maxPathLength", ANARI_INT32, "surface interactions per path", &kPathLength},
             {"volumeAnisotropy", ANARI_FLOAT32, "Henyey-Greenstein mean cosine of volume scattering, in (-1, 1); 0: isotropic"},
             {"maxRadiance", ANARI_FLOAT32, "largest component of one contribution (biased, less noise); 0: off",
              &kZero},
             {"seed", ANARI_UINT32, "varies the random numbers; images with different seeds share no samples", &kSeed},
         }})},
        {ANARI_RENDERER, "eyeLight", "quick look: the first surface or volume collision lit from the eye, no bounces",
         joined({kName, {
             {"background", ANARI_FLOAT32_VEC4, "colour seen by camera rays that miss", kOpaqueBlack},
             {"ambientColor", ANARI_FLOAT32_VEC3, "colour of the light at the eye", kWhite},
             {"ambientRadiance", ANARI_FLOAT32, "radiance of the light at the eye", &kOne},
             {"eyeLightBlendRatio", ANARI_FLOAT32, "share of the light that falls off as |cos| of the view angle, in [0, 1]", &kHalf},
             {"pixelSamples", ANARI_INT32, "samples per pixel added by each anariRenderFrame", &kOneSample},
             {"seed", ANARI_UINT32, "varies the random numbers; images with different seeds share no samples", &kSeed},
         }})},
        {ANARI_SURFACE, "", "a geometry with its material",
         joined({kName, {
             {"geometry", ANARI_GEOMETRY, "the geometry", nullptr, nullptr, true},
             {"material", ANARI_MATERIAL, "the material", nullptr, nullptr, true},
             {"visible", ANARI_BOOL, "whether it renders", &kTrue},
             {"id", ANARI_UINT32, "object id for the objectId channel; ~0u when unset"},
         }})},
        {ANARI_SPATIAL_FIELD, "structuredRegular", "cell-vertex samples on a regular grid",
         joined({kName, {
             {"data", ANARI_ARRAY3D, "samples (UFIXED8, FIXED16, UFIXED16, FLOAT32, FLOAT64)", nullptr, nullptr, true},
             {"origin", ANARI_FLOAT32_VEC3, "object-space position of sample (0, 0, 0)"},
             {"spacing", ANARI_FLOAT32_VEC3, "distance between samples along each axis"},
             {"filter", ANARI_STRING, "sample interpolation", "linear", kFilters},
         }})},
        {ANARI_SPATIAL_FIELD, "unstructured", "tetrahedra, hexahedra, wedges and pyramids with values per vertex or per cell",
         joined({kName, {
             {"vertex.position", ANARI_ARRAY1D, "vertex positions (FLOAT32_VEC3)", nullptr, nullptr, true},
             {"vertex.data", ANARI_ARRAY1D, "values per vertex (UFIXED8, FIXED16, UFIXED16, FLOAT32, FLOAT64)"},
             {"cell.data", ANARI_ARRAY1D, "values per cell, constant over it (when no vertex.data)"},
             {"index", ANARI_ARRAY1D, "the cells' vertex indices (UINT32)", nullptr, nullptr, true},
             {"cell.index", ANARI_ARRAY1D, "each cell's first entry in index (UINT32)", nullptr, nullptr, true},
             {"cell.type", ANARI_ARRAY1D, "each cell's VTK type: 10 tetrahedron, 12 hexahedron, 13 wedge, 14 pyramid (UINT8)",
              nullptr, nullptr, true},
         }})},
        {ANARI_SPATIAL_FIELD, "nanovdb", "a NanoVDB float grid, sparse: only its leaves and tiles are stored",
         joined({kName, {
             {"data", ANARI_ARRAY1D, "the NanoVDB grid buffer (UINT8)", nullptr, nullptr, true},
             {"filter", ANARI_STRING, "sample interpolation", "linear", kFilters},
         }})},
        {ANARI_SPATIAL_FIELD, "amr", "a block-structured AMR hierarchy: the finest covering cell's value",
         joined({kName, {
             {"cellWidth", ANARI_ARRAY1D, "cell width per level, decreasing (FLOAT32)", nullptr, nullptr, true},
             {"block.bounds", ANARI_ARRAY1D, "each block's cells in its level's index space, inclusive (INT32_BOX3)", nullptr, nullptr, true},
             {"block.level", ANARI_ARRAY1D, "each block's level (INT32)", nullptr, nullptr, true},
             {"block.data", ANARI_ARRAY1D, "each block's cell values (ARRAY3D)", nullptr, nullptr, true},
             {"origin", ANARI_FLOAT32_VEC3, "object-space position of index (0, 0, 0)"},
             {"spacing", ANARI_FLOAT32_VEC3, "object-space size of a cell of width 1"},
         }})},
        {ANARI_VOLUME, "transferFunction1D", "a scalar field as a scattering medium: albedo and opacity from the value",
         joined({kName, {
             {"value", ANARI_SPATIAL_FIELD, "the field", nullptr, nullptr, true},
             {"valueRange", ANARI_FLOAT32_BOX1, "values mapped to the ends of color and opacity"},
             {"color", ANARI_FLOAT32_VEC3, "uniform albedo"},
             {"color", ANARI_ARRAY1D, "albedo over the value range"},
             {"opacity", ANARI_FLOAT32, "uniform opacity", &kOne},
             {"opacity", ANARI_ARRAY1D, "opacity over the value range (FLOAT32)"},
             {"unitDistance", ANARI_FLOAT32, "distance over which opacity o lets 1 - o through", &kOne},
             {"visible", ANARI_BOOL, "whether it renders", &kTrue},
             {"id", ANARI_UINT32, "object id for the objectId channel where it scatters; ~0u when unset"},
         }})},
        {ANARI_GROUP, "", "surfaces, volumes and lights placed together by instances",
         joined({kName, {
             {"surface", ANARI_ARRAY1D, "surfaces (ANARI_SURFACE)"},
             {"volume", ANARI_ARRAY1D, "volumes (ANARI_VOLUME)"},
             {"light", ANARI_ARRAY1D, "lights (ANARI_LIGHT)"},
         }})},
        {ANARI_WORLD, "", "everything a frame renders",
         joined({kName, {
             {"instance", ANARI_ARRAY1D, "instances (ANARI_INSTANCE)"},
             {"surface", ANARI_ARRAY1D, "surfaces placed without an instance"},
             {"volume", ANARI_ARRAY1D, "volumes placed without an instance"},
             {"light", ANARI_ARRAY1D, "lights placed without an instance"},
         }})},
        {ANARI_FRAME, "", "an image rendered asynchronously, accumulating while nothing changes",
         joined({kName, {
             {"world", ANARI_WORLD, "what to render", nullptr, nullptr, true},
             {"camera", ANARI_CAMERA, "the view", nullptr, nullptr, true},
             {"renderer", ANARI_RENDERER, "how", nullptr, nullptr, true},
             {"size", ANARI_UINT32_VEC2, "width and height in pixels", nullptr, nullptr, true},
             {"channel.color", ANARI_DATA_TYPE, "UFIXED8_VEC4, UFIXED8_RGBA_SRGB or FLOAT32_VEC4"},
             {"channel.depth", ANARI_DATA_TYPE, "FLOAT32: distance to the first hit"},
             {"channel.albedo", ANARI_DATA_TYPE, "FLOAT32_VEC3: base colour at the first hit"},
             {"channel.normal", ANARI_DATA_TYPE, "FLOAT32_VEC3: world-space shading normal at the first hit"},
             {"channel.primitiveId", ANARI_DATA_TYPE, "UINT32: primitive index at the first hit (~0u: none)"},
             {"channel.objectId", ANARI_DATA_TYPE, "UINT32: the surface's id at the first hit (~0u: none)"},
             {"channel.instanceId", ANARI_DATA_TYPE, "UINT32: the instance's id at the first hit (~0u: none)"},
         }})},
    };
    return entries;
}

bool sameSubtype(const char* a, const char* b) {
    return std::string_view(a ? a : "") == std::string_view(b ? b : "");
}

const Entry* find(ANARIDataType type, const char* subtype) {
    for (const Entry& entry : table())
        if (entry.type == type && sameSubtype(entry.subtype, subtype)) return &entry;
    return nullptr;
}

}  // namespace

const char** deviceSubtypes() {
    static const char* subtypes[] = {"default", nullptr};
    return subtypes;
}

const char** deviceExtensions() {
    static const char* extensions[] = {
        "ANARI_KHR_GEOMETRY_TRIANGLE",    "ANARI_KHR_GEOMETRY_QUAD",          "ANARI_KHR_GEOMETRY_SPHERE",
        "ANARI_KHR_GEOMETRY_CYLINDER",    "ANARI_KHR_MATERIAL_MATTE",         "ANARI_KHR_MATERIAL_PHYSICALLY_BASED",
        "ANARI_KHR_SAMPLER_IMAGE2D",      "ANARI_KHR_LIGHT_DIRECTIONAL",      "ANARI_KHR_LIGHT_POINT",
        "ANARI_KHR_LIGHT_QUAD",           "ANARI_KHR_LIGHT_SPOT",             "ANARI_KHR_LIGHT_RING",           "ANARI_KHR_LIGHT_HDRI",           "ANARI_KHR_SAMPLER_IMAGE1D",  "ANARI_KHR_SAMPLER_IMAGE3D",  "ANARI_KHR_SAMPLER_PRIMITIVE",  "ANARI_KHR_SAMPLER_TRANSFORM",           "ANARI_KHR_CAMERA_PERSPECTIVE",     "ANARI_KHR_CAMERA_ORTHOGRAPHIC",
        "ANARI_KHR_INSTANCE_TRANSFORM",   "ANARI_KHR_RENDERER_BACKGROUND_COLOR", "ANARI_KHR_RENDERER_AMBIENT_LIGHT",
        "ANARI_KHR_GEOMETRY_CONE",        "ANARI_KHR_GEOMETRY_CURVE",         "ANARI_KHR_CAMERA_OMNIDIRECTIONAL",
        "ANARI_KHR_CAMERA_DEPTH_OF_FIELD", "ANARI_KHR_FRAME_CHANNEL_ALBEDO",  "ANARI_KHR_FRAME_CHANNEL_NORMAL",
        "ANARI_KHR_FRAME_CHANNEL_PRIMITIVE_ID", "ANARI_KHR_FRAME_CHANNEL_OBJECT_ID", "ANARI_KHR_FRAME_CHANNEL_INSTANCE_ID",
        "ANARI_KHR_DATA_PARALLEL_MPI",    "ANARI_KHR_FRAME_ACCUMULATION",     "ANARI_KHR_DEVICE_SYNCHRONIZATION",
        "ANARI_KHR_FRAME_COMPLETION_CALLBACK", "ANARI_KHR_SPATIAL_FIELD_STRUCTURED_REGULAR", "ANARI_KHR_SPATIAL_FIELD_UNSTRUCTURED", "ANARI_KHR_SPATIAL_FIELD_NANOVDB",
        "ANARI_RIPPLE_SPATIAL_FIELD_AMR",
        "ANARI_KHR_VOLUME_TRANSFER_FUNCTION1D", "ANARI_KHR_GEOMETRY_ISOSURFACE",
        nullptr};
    return extensions;
}

const char** objectSubtypes(ANARIDataType objectType) {
    static const std::map<ANARIDataType, std::vector<const char*>> lists = [] {
        std::map<ANARIDataType, std::vector<const char*>> byType;
        for (const Entry& entry : table())
            if (entry.subtype[0] != '\0') byType[entry.type].push_back(entry.subtype);
        for (auto& [type, names] : byType) names.push_back(nullptr);
        return byType;
    }();
    auto it = lists.find(objectType);
    return it == lists.end() ? nullptr : const_cast<const char**>(it->second.data());
}

const void* objectInfo(ANARIDataType objectType, const char* subtype, const char* infoName, ANARIDataType infoType) {
    const Entry* entry = find(objectType, subtype);
    if (!entry || !infoName) return nullptr;
    const std::string_view info = infoName;
    if (info == "description" && infoType == ANARI_STRING) return entry->description;
    if (info == "parameter" && infoType == ANARI_PARAMETER_LIST) {
        static const std::map<const Entry*, std::vector<ANARIParameter>> lists = [] {
            std::map<const Entry*, std::vector<ANARIParameter>> byEntry;
            for (const Entry& e : table()) {
                std::vector<ANARIParameter>& list = byEntry[&e];
                for (const Param& p : e.parameters) list.push_back(ANARIParameter{p.name, p.type});
                list.push_back(ANARIParameter{nullptr, ANARI_UNKNOWN});
            }
            return byEntry;
        }();
        return lists.at(entry).data();
    }
    return nullptr;
}

const void* parameterInfo(ANARIDataType objectType, const char* subtype, const char* parameterName,
                          ANARIDataType parameterType, const char* infoName, ANARIDataType infoType) {
    const Entry* entry = find(objectType, subtype);
    if (!entry || !parameterName || !infoName) return nullptr;
    const Param* param = nullptr;
    for (const Param& p : entry->parameters)
        if (std::strcmp(p.name, parameterName) == 0 && p.type == parameterType) param = &p;
    if (!param) return nullptr;
    const std::string_view info = infoName;
    if (info == "description" && infoType == ANARI_STRING) return param->description;
    if (info == "required" && infoType == ANARI_BOOL) return param->required ? &kTrue : &kFalse;
    if (info == "default" && infoType == parameterType) return param->defaultValue;
    if (info == "value" && infoType == ANARI_STRING_LIST) return param->values;
    return nullptr;
}

}  // namespace ripple::device
