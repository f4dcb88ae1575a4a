// The subtype table behind createObject (see ObjectFactory.h). Introspection lists the same subtypes;
// the render tests check that every listed subtype is created without the unknown-subtype warning.
#include "anari/device/ObjectFactory.h"

#include "anari/device/camera/Camera.h"
#include "anari/device/frame/Frame.h"
#include "anari/device/geometry/Geometry.h"
#include "anari/device/group/Group.h"
#include "anari/device/instance/Instance.h"
#include "anari/device/light/Light.h"
#include "anari/device/material/Material.h"
#include "anari/device/renderer/Renderer.h"
#include "anari/device/sampler/Sampler.h"
#include "anari/device/surface/Surface.h"
#include "anari/device/volume/AmrField.h"
#include "anari/device/volume/NanoVdbField.h"
#include "anari/device/volume/StructuredRegularField.h"
#include "anari/device/volume/UnstructuredField.h"
#include "anari/device/volume/Volume.h"
#include "anari/device/world/World.h"

#include <cctype>
#include <string>

namespace ripple::device {
namespace {

// A subtype Ripple does not implement (or a whole object type, like volumes): it takes parameters like any
// object, so applications run on, but it is never valid, so nothing renders from it.
class UnknownObject final : public Object {
public:
    UnknownObject(DeviceState& state, ANARIDataType type, std::string_view subtype, const std::string& why)
        : Object(state, type, std::string(subtype)) {
        reportWarning(why + "; it renders nothing");
    }
    bool isValid() const override { return false; }
};

struct Subtype {
    ANARIDataType type;
    std::string_view name;
    Object* (*create)(DeviceState&);
};

template <class T>
Object* make(DeviceState& state) {
    return new T(state);
}

constexpr Subtype kSubtypes[] = {
    {ANARI_GEOMETRY, "triangle", [](DeviceState& s) -> Object* { return newTriangleGeometry(s); }},
    {ANARI_GEOMETRY, "quad", [](DeviceState& s) -> Object* { return newQuadGeometry(s); }},
    {ANARI_GEOMETRY, "sphere", [](DeviceState& s) -> Object* { return newSphereGeometry(s); }},
    {ANARI_GEOMETRY, "cylinder", [](DeviceState& s) -> Object* { return newCylinderGeometry(s); }},
    {ANARI_GEOMETRY, "cone", [](DeviceState& s) -> Object* { return newConeGeometry(s); }},
    {ANARI_GEOMETRY, "curve", [](DeviceState& s) -> Object* { return newCurveGeometry(s); }},
    {ANARI_GEOMETRY, "isosurface", [](DeviceState& s) -> Object* { return newIsosurfaceGeometry(s); }},
    {ANARI_MATERIAL, "matte", [](DeviceState& s) -> Object* { return newMatteMaterial(s); }},
    {ANARI_MATERIAL, "physicallyBased", [](DeviceState& s) -> Object* { return newPhysicallyBasedMaterial(s); }},
    {ANARI_SAMPLER, "image1D", [](DeviceState& s) -> Object* { return newImageSampler(s, 1); }},
    {ANARI_SAMPLER, "image2D", [](DeviceState& s) -> Object* { return newImageSampler(s, 2); }},
    {ANARI_SAMPLER, "image3D", [](DeviceState& s) -> Object* { return newImageSampler(s, 3); }},
    {ANARI_SAMPLER, "transform", [](DeviceState& s) -> Object* { return newTransformSampler(s); }},
    {ANARI_SAMPLER, "primitive", [](DeviceState& s) -> Object* { return newPrimitiveSampler(s); }},
    {ANARI_LIGHT, "directional", [](DeviceState& s) -> Object* { return newDirectionalLight(s); }},
    {ANARI_LIGHT, "point", [](DeviceState& s) -> Object* { return newPointLight(s); }},
    {ANARI_LIGHT, "quad", [](DeviceState& s) -> Object* { return newQuadLight(s); }},
    {ANARI_LIGHT, "spot", [](DeviceState& s) -> Object* { return newSpotLight(s); }},
    {ANARI_LIGHT, "ring", [](DeviceState& s) -> Object* { return newRingLight(s); }},
    {ANARI_LIGHT, "hdri", [](DeviceState& s) -> Object* { return newHdriLight(s); }},
    {ANARI_CAMERA, "perspective", [](DeviceState& s) -> Object* { return newPerspectiveCamera(s); }},
    {ANARI_CAMERA, "orthographic", [](DeviceState& s) -> Object* { return newOrthographicCamera(s); }},
    {ANARI_CAMERA, "omnidirectional", [](DeviceState& s) -> Object* { return newOmnidirectionalCamera(s); }},
    {ANARI_INSTANCE, "transform", [](DeviceState& s) -> Object* { return newTransformInstance(s); }},
    {ANARI_SPATIAL_FIELD, "structuredRegular", make<StructuredRegularField>},
    {ANARI_SPATIAL_FIELD, "unstructured", make<UnstructuredField>},
    {ANARI_SPATIAL_FIELD, "nanovdb", make<NanoVdbField>},
    {ANARI_SPATIAL_FIELD, "amr", make<AmrField>},
    {ANARI_VOLUME, "transferFunction1D", make<Volume>},
    {ANARI_RENDERER, "default", [](DeviceState& s) -> Object* { return new Renderer(s, "default"); }},
    {ANARI_RENDERER, "eyeLight", [](DeviceState& s) -> Object* { return new Renderer(s, "eyeLight"); }},
    {ANARI_SURFACE, "", make<Surface>},
    {ANARI_GROUP, "", make<Group>},
    {ANARI_WORLD, "", make<World>},
    {ANARI_FRAME, "", make<Frame>},
};

std::string typeWord(ANARIDataType type) {
    // "ANARI_SPATIAL_FIELD" -> "spatial_field": how messages name an object type.
    std::string name = ripple_anari::typeName(type);
    if (name.rfind("ANARI_", 0) == 0) name.erase(0, 6);
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    return name;
}

}  // namespace

Object* createObject(DeviceState& state, ANARIDataType objectType, std::string_view subtype) {
    bool typeKnown = false;
    for (const Subtype& entry : kSubtypes) {
        if (entry.type != objectType) continue;
        typeKnown = true;
        if (entry.name == subtype) return entry.create(state);
    }
    const std::string why = typeKnown ? "unknown " + typeWord(objectType) + " subtype '" + std::string(subtype) + "'"
                                      : typeWord(objectType) + " objects are not supported by Ripple yet";
    return new UnknownObject(state, objectType, subtype, why);
}

}  // namespace ripple::device
