// Definitions of the ANARI C functions the scene builders call, recording instead of rendering. Functions
// the builders do not use are left undefined on purpose: a new call shows up as a link error here.
#include "tests/apps/FakeAnari.h"

#include <anari/anari_type_traits.hpp>

#include <cstring>

namespace ripple::test {

namespace {

std::unique_ptr<FakeDevice> current;
int deviceToken;  // its address is the one device handle

FakeObject* create(ANARIDataType type, const char* subtype) {
    auto object = std::make_unique<FakeObject>();
    object->type = type;
    object->subtype = subtype ? subtype : "";
    current->objects.push_back(std::move(object));
    return current->objects.back().get();
}

template <typename Handle>
Handle handle(FakeObject* object) {
    return reinterpret_cast<Handle>(object);
}

FakeObject* live(ANARIObject h, const char* call) {
    auto* object = reinterpret_cast<FakeObject*>(h);
    if (!object) current->misuse.push_back(std::string(call) + " on a null handle");
    else if (object->appReferences <= 0) current->misuse.push_back(std::string(call) + " after release");
    return object;
}

FakeObject* newArray(ANARIDataType arrayType, const void* appMemory, ANARIDataType elementType, uint64_t n1,
                     uint64_t n2) {
    FakeObject* a = create(arrayType, nullptr);
    a->elementType = elementType;
    a->count1 = n1;
    a->count2 = n2;
    a->data.resize(ripple_anari::sizeOf(elementType) * n1 * n2);
    if (appMemory) std::memcpy(a->data.data(), appMemory, a->data.size());
    return a;
}

}  // namespace

std::vector<const FakeObject*> FakeDevice::ofType(ANARIDataType type, const std::string& subtype) const {
    std::vector<const FakeObject*> out;
    for (const auto& o : objects)
        if (o->type == type && (subtype == "*" || o->subtype == subtype)) out.push_back(o.get());
    return out;
}

ANARIDevice newFakeDevice() {
    current = std::make_unique<FakeDevice>();
    return reinterpret_cast<ANARIDevice>(&deviceToken);
}

FakeDevice& fakeDevice() { return *current; }

const FakeObject* fakeObject(ANARIObject h) { return reinterpret_cast<const FakeObject*>(h); }

}  // namespace ripple::test

using namespace ripple::test;

extern "C" {

ANARIArray1D anariNewArray1D(ANARIDevice, const void* appMemory, ANARIMemoryDeleter, const void*, ANARIDataType type,
                             uint64_t n1) {
    return handle<ANARIArray1D>(newArray(ANARI_ARRAY1D, appMemory, type, n1, 1));
}

ANARIArray2D anariNewArray2D(ANARIDevice, const void* appMemory, ANARIMemoryDeleter, const void*, ANARIDataType type,
                             uint64_t n1, uint64_t n2) {
    return handle<ANARIArray2D>(newArray(ANARI_ARRAY2D, appMemory, type, n1, n2));
}

// A 3D array's second and third dimensions are folded into count2.
ANARIArray3D anariNewArray3D(ANARIDevice, const void* appMemory, ANARIMemoryDeleter, const void*, ANARIDataType type,
                             uint64_t n1, uint64_t n2, uint64_t n3) {
    return handle<ANARIArray3D>(newArray(ANARI_ARRAY3D, appMemory, type, n1, n2 * n3));
}

void* anariMapArray(ANARIDevice, ANARIArray array) {
    FakeObject* a = live(array, "anariMapArray");
    return a ? a->data.data() : nullptr;
}

void anariUnmapArray(ANARIDevice, ANARIArray array) { live(array, "anariUnmapArray"); }

ANARILight anariNewLight(ANARIDevice, const char* type) { return handle<ANARILight>(create(ANARI_LIGHT, type)); }
ANARICamera anariNewCamera(ANARIDevice, const char* type) { return handle<ANARICamera>(create(ANARI_CAMERA, type)); }
ANARIGeometry anariNewGeometry(ANARIDevice, const char* type) { return handle<ANARIGeometry>(create(ANARI_GEOMETRY, type)); }
ANARISurface anariNewSurface(ANARIDevice) { return handle<ANARISurface>(create(ANARI_SURFACE, nullptr)); }
ANARIMaterial anariNewMaterial(ANARIDevice, const char* type) { return handle<ANARIMaterial>(create(ANARI_MATERIAL, type)); }
ANARISampler anariNewSampler(ANARIDevice, const char* type) { return handle<ANARISampler>(create(ANARI_SAMPLER, type)); }
ANARISpatialField anariNewSpatialField(ANARIDevice, const char* type) {
    return handle<ANARISpatialField>(create(ANARI_SPATIAL_FIELD, type));
}
ANARIVolume anariNewVolume(ANARIDevice, const char* type) { return handle<ANARIVolume>(create(ANARI_VOLUME, type)); }
ANARIGroup anariNewGroup(ANARIDevice) { return handle<ANARIGroup>(create(ANARI_GROUP, nullptr)); }
ANARIInstance anariNewInstance(ANARIDevice, const char* type) { return handle<ANARIInstance>(create(ANARI_INSTANCE, type)); }
ANARIWorld anariNewWorld(ANARIDevice) { return handle<ANARIWorld>(create(ANARI_WORLD, nullptr)); }

void anariSetParameter(ANARIDevice, ANARIObject object, const char* name, ANARIDataType type, const void* mem) {
    FakeObject* o = live(object, "anariSetParameter");
    if (!o || !name || !mem) return;
    FakeParameter p;
    p.type = type;
    if (type == ANARI_STRING) {
        p.text = static_cast<const char*>(mem);
    } else if (type >= ANARI_OBJECT && type <= ANARI_WORLD) {
        ANARIObject value;
        std::memcpy(&value, mem, sizeof value);
        p.object = live(value, (std::string("anariSetParameter '") + name + "' with an object").c_str());
    } else {
        const auto* bytes = static_cast<const uint8_t*>(mem);
        p.bytes.assign(bytes, bytes + ripple_anari::sizeOf(type));
    }
    o->parameters[name] = p;
}

void anariUnsetParameter(ANARIDevice, ANARIObject object, const char* name) {
    if (FakeObject* o = live(object, "anariUnsetParameter"); o && name) o->parameters.erase(name);
}

void anariCommitParameters(ANARIDevice, ANARIObject object) {
    if (FakeObject* o = live(object, "anariCommitParameters")) o->committed = true;
}

void anariRelease(ANARIDevice, ANARIObject object) {
    if (FakeObject* o = live(object, "anariRelease")) --o->appReferences;
}

void anariRetain(ANARIDevice, ANARIObject object) {
    if (FakeObject* o = live(object, "anariRetain")) ++o->appReferences;
}

}  // extern "C"
