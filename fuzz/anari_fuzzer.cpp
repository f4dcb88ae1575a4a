// libFuzzer target: the Ripple device through the public ANARI C API and Ripple's loader, the input read as
// a sequence of legal calls on a pool of handles. Nothing is rendered, so one execution takes milliseconds.
//
// Legal means: a handle is passed only while the fuzzer holds a reference to it, app memory is as large as
// the array it backs and outlives the array (freed by the deleter, or after the last release when there is
// none), a stated object type is the handle's real type, and every map is followed by its unmap. Values,
// parameter names and types are free: the device must report bad ones, never crash. Set RIPPLE_FUZZ_VERBOSE=1
// to print the calls and the device's messages while reproducing a case. RIPPLE_FUZZ_AVOID (comma-separated)
// leaves out calls that reach a known, not yet fixed finding, so a run can look past it:
//   map-parameter-array   anariMapParameterArray1D
//   wrong-handle-type     a handle set on a parameter that does not list its type (it can point at itself)
#include "anari/anari.h"
#include "anari/anari_type_traits.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

bool gVerbose = false;
bool gAvoidMapParameterArray = false;
bool gAvoidWrongHandleType = false;
ANARILibrary gLibrary = nullptr;

void statusCallback(const void*, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
                    ANARIStatusCode, const char* message) {
    if (gVerbose) std::fprintf(stderr, "  status %d: %s\n", int(severity), message);
}

#define TRACE(...)                                    \
    do {                                              \
        if (gVerbose) std::fprintf(stderr, __VA_ARGS__); \
    } while (0)

// The input as a stream of choices; past its end every read is 0, so every input is a whole program.
class Input {
public:
    Input(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    bool done() const { return at_ >= size_; }
    uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    size_t below(size_t n) { return n ? byte() % n : 0; }
    void fill(void* out, size_t bytes) {
        const size_t take = std::min(bytes, size_ - std::min(at_, size_));
        if (take) std::memcpy(out, data_ + at_, take);
        std::memset(static_cast<uint8_t*>(out) + take, 0, bytes - take);
        at_ += take;
    }

private:
    const uint8_t* data_;
    size_t size_;
    size_t at_ = 0;
};

// What the device says about itself, read once through introspection: subtypes and their parameters.
struct Subtype {
    ANARIDataType type;
    std::string name;  // "" for types without subtypes
    std::vector<ANARIParameter> parameters;
};
std::vector<Subtype> gSubtypes;

const ANARIDataType kObjectTypes[] = {ANARI_CAMERA,   ANARI_GEOMETRY,      ANARI_LIGHT,  ANARI_MATERIAL,
                                      ANARI_SAMPLER,  ANARI_SPATIAL_FIELD, ANARI_VOLUME, ANARI_INSTANCE,
                                      ANARI_RENDERER, ANARI_SURFACE,       ANARI_GROUP,  ANARI_WORLD,
                                      ANARI_FRAME};

// Types a parameter or array element may be given besides the one introspection lists.
const ANARIDataType kValueTypes[] = {
    ANARI_BOOL,         ANARI_INT32,         ANARI_UINT32,       ANARI_UINT32_VEC2,   ANARI_UINT32_VEC3,
    ANARI_UINT32_VEC4,  ANARI_INT32_VEC2,    ANARI_UINT8,        ANARI_UINT8_VEC4,    ANARI_UINT16,
    ANARI_UINT64,       ANARI_FLOAT32,       ANARI_FLOAT32_VEC2, ANARI_FLOAT32_VEC3,  ANARI_FLOAT32_VEC4,
    ANARI_FLOAT64,      ANARI_FLOAT32_MAT4,  ANARI_FLOAT32_MAT3x4, ANARI_FLOAT32_BOX3, ANARI_UFIXED8_RGBA_SRGB,
    ANARI_FLOAT16,      ANARI_STRING,        ANARI_DATA_TYPE,    ANARI_ARRAY1D,       ANARI_ARRAY2D,
    ANARI_ARRAY3D,      ANARI_GEOMETRY,      ANARI_MATERIAL,     ANARI_SAMPLER,       ANARI_SURFACE,
    ANARI_INSTANCE,     ANARI_GROUP,         ANARI_LIGHT,        ANARI_CAMERA,        ANARI_WORLD,
    ANARI_RENDERER,     ANARI_SPATIAL_FIELD, ANARI_VOLUME,       ANARI_OBJECT,        ANARI_INT8};

const char* const kExtraNames[] = {"name", "", "bogus", "vertex.position", "primitive.index", "color", "transform"};

void readIntrospection(ANARIDevice device) {
    for (ANARIDataType type : kObjectTypes) {
        std::vector<std::string> names;
        if (const char** list = anariGetObjectSubtypes(device, type))
            for (; *list; ++list) names.emplace_back(*list);
        if (names.empty()) names.emplace_back("");
        for (const std::string& name : names) {
            Subtype s{type, name, {}};
            const void* info = anariGetObjectInfo(device, type, name.empty() ? nullptr : name.c_str(), "parameter",
                                                  ANARI_PARAMETER_LIST);
            for (auto* p = static_cast<const ANARIParameter*>(info); p && p->name; ++p) s.parameters.push_back(*p);
            gSubtypes.push_back(std::move(s));
        }
    }
}

struct Slot {
    ANARIObject handle = nullptr;
    ANARIDataType type = ANARI_UNKNOWN;
    const Subtype* subtype = nullptr;  // nullptr for arrays
    int references = 0;                // the fuzzer's own
    ANARIDataType elementType = ANARI_UNKNOWN;
    uint64_t elements = 0;
    void* ownedMemory = nullptr;       // app memory without a deleter: freed after the last release
};

void deleter(const void*, const void* appMemory) { std::free(const_cast<void*>(appMemory)); }

class Session {
public:
    explicit Session(ANARIDevice device) : device_(device) {}
    ~Session() {
        for (size_t i = 0; i < slots_.size(); ++i) clear(i);
    }

    void step(Input& in) {
        switch (in.below(12)) {
            case 0: newObject(in); break;
            case 1: newArray(in); break;
            case 2:
            case 3: setParameter(in); break;
            case 4: unsetParameter(in); break;
            case 5: {
                if (Slot* s = live(in)) {
                    TRACE("unsetAll %p\n", (void*)s->handle);
                    anariUnsetAllParameters(device_, s->handle);
                }
                break;
            }
            case 6:
            case 7: {
                if (Slot* s = live(in)) {
                    TRACE("commit %p\n", (void*)s->handle);
                    anariCommitParameters(device_, s->handle);
                }
                break;
            }
            case 8: {
                if (Slot* s = live(in); s && s->references < 4) {
                    TRACE("retain %p\n", (void*)s->handle);
                    anariRetain(device_, s->handle);
                    ++s->references;
                }
                break;
            }
            case 9: {
                const size_t i = in.below(kSlots);
                if (slots_[i].handle) release(i);
                break;
            }
            case 10: mapArray(in); break;
            case 11: {
                if (in.below(2)) mapParameterArray(in);
                else getProperty(in);
                break;
            }
        }
    }

private:
    static constexpr size_t kSlots = 8;

    Slot* live(Input& in) {
        Slot& s = slots_[in.below(kSlots)];
        return s.handle ? &s : nullptr;
    }

    void release(size_t i) {
        Slot& s = slots_[i];
        TRACE("release %p\n", (void*)s.handle);
        anariRelease(device_, s.handle);
        if (--s.references == 0) {
            std::free(s.ownedMemory);
            s = Slot{};
        }
    }
    void clear(size_t i) {
        while (slots_[i].handle) release(i);
    }

    // A live handle whose type fits `type` (ANARI_OBJECT: any; ANARI_ARRAY: any array), or nullptr.
    Slot* liveOfType(Input& in, ANARIDataType type) {
        std::vector<Slot*> fits;
        for (Slot& s : slots_) {
            if (!s.handle) continue;
            const bool isArray = s.type >= ANARI_ARRAY1D && s.type <= ANARI_ARRAY3D;
            if (s.type == type || type == ANARI_OBJECT || (type == ANARI_ARRAY && isArray)) fits.push_back(&s);
        }
        return fits.empty() ? nullptr : fits[in.below(fits.size())];
    }

    void newObject(Input& in) {
        const size_t i = in.below(kSlots);
        clear(i);
        const Subtype& st = gSubtypes[in.below(gSubtypes.size())];
        // One in 16 asks for a subtype the device does not have: it must answer with an object that reports.
        const std::string subtype = (!st.name.empty() && in.below(16) == 0) ? std::string("fuzz") : st.name;
        const char* name = subtype.c_str();
        ANARIObject h = nullptr;
        switch (st.type) {
            case ANARI_CAMERA: h = anariNewCamera(device_, name); break;
            case ANARI_GEOMETRY: h = anariNewGeometry(device_, name); break;
            case ANARI_LIGHT: h = anariNewLight(device_, name); break;
            case ANARI_MATERIAL: h = anariNewMaterial(device_, name); break;
            case ANARI_SAMPLER: h = anariNewSampler(device_, name); break;
            case ANARI_SPATIAL_FIELD: h = anariNewSpatialField(device_, name); break;
            case ANARI_VOLUME: h = anariNewVolume(device_, name); break;
            case ANARI_INSTANCE: h = anariNewInstance(device_, name); break;
            case ANARI_RENDERER: h = anariNewRenderer(device_, name); break;
            case ANARI_SURFACE: h = anariNewSurface(device_); break;
            case ANARI_GROUP: h = anariNewGroup(device_); break;
            case ANARI_WORLD: h = anariNewWorld(device_); break;
            case ANARI_FRAME: h = anariNewFrame(device_); break;
            default: break;
        }
        TRACE("new %s '%s' -> slot %zu %p\n", ripple_anari::typeName(st.type), name, i, (void*)h);
        if (!h) return;
        slots_[i] = Slot{h, st.type, &st, 1, ANARI_UNKNOWN, 0, nullptr};
    }

    // Writes `count` elements of `type` at `out` (stride apart): handles of live objects for object types,
    // input bytes otherwise. False when an object array cannot be filled legally (no live object of that type).
    bool fillElements(Input& in, void* out, ANARIDataType type, uint64_t count, uint64_t stride) {
        auto* bytes = static_cast<uint8_t*>(out);
        const size_t size = ripple_anari::sizeOf(type);
        for (uint64_t e = 0; e < count; ++e) {
            if (ripple_anari::isObjectType(type)) {
                Slot* s = liveOfType(in, type);
                if (!s) return false;
                std::memcpy(bytes + e * stride, &s->handle, sizeof(ANARIObject));
            } else {
                in.fill(bytes + e * stride, size);
            }
        }
        return true;
    }

    void newArray(Input& in) {
        const size_t i = in.below(kSlots);
        clear(i);
        const int dims = 1 + int(in.below(3));
        // Up to 16 per dimension; 0 is a legal request the device must refuse or accept without harm.
        uint64_t n[3] = {1 + in.below(16), 1, 1};
        if (in.below(32) == 0) n[0] = 0;
        for (int d = 1; d < dims; ++d) n[d] = 1 + in.below(8);
        const ANARIDataType type = kValueTypes[in.below(std::size(kValueTypes))];
        const size_t size = ripple_anari::sizeOf(type);
        if (type == ANARI_STRING || type == ANARI_ARRAY1D || type == ANARI_ARRAY2D || type == ANARI_ARRAY3D ||
            type == ANARI_OBJECT || size == 0)
            return;  // not element types of ANARI arrays
        const uint64_t count = n[0] * n[1] * n[2];
        const int memory = int(in.below(3));  // 0: device-managed, 1: app memory + deleter, 2: app memory, no deleter
        void* app = nullptr;
        if (memory != 0) {
            app = std::calloc(std::max<uint64_t>(count * size, 1), 1);
            if (!fillElements(in, app, type, count, size)) {
                std::free(app);
                return;
            }
        }
        ANARIMemoryDeleter del = memory == 1 ? &deleter : nullptr;
        ANARIArray a = nullptr;
        if (dims == 1) a = anariNewArray1D(device_, app, del, nullptr, type, n[0]);
        else if (dims == 2) a = anariNewArray2D(device_, app, del, nullptr, type, n[0], n[1]);
        else a = anariNewArray3D(device_, app, del, nullptr, type, n[0], n[1], n[2]);
        TRACE("newArray%dD %s %llux%llux%llu memory %d -> slot %zu %p\n", dims, ripple_anari::typeName(type),
              (unsigned long long)n[0], (unsigned long long)n[1], (unsigned long long)n[2], memory, i, (void*)a);
        if (!a) {
            // A refused array never took the memory (Ripple calls no deleter for an array it did not make).
            std::free(app);
            return;
        }
        const ANARIDataType arrayType = dims == 1 ? ANARI_ARRAY1D : dims == 2 ? ANARI_ARRAY2D : ANARI_ARRAY3D;
        slots_[i] = Slot{a, arrayType, nullptr, 1, type, count, memory == 2 ? app : nullptr};
        if (memory == 0) {
            // Device-managed memory starts undefined; object arrays must hold valid handles before use.
            void* p = anariMapArray(device_, a);
            if (p && !fillElements(in, p, type, count, size)) std::memset(p, 0, count * size);
            anariUnmapArray(device_, a);
        }
    }

    void mapArray(Input& in) {
        Slot* s = live(in);
        if (!s || s->subtype) return;
        const auto array = reinterpret_cast<ANARIArray>(s->handle);
        void* p = anariMapArray(device_, array);
        TRACE("mapArray %p -> %p\n", (void*)s->handle, p);
        const size_t size = ripple_anari::sizeOf(s->elementType);
        // Handles are written only when every element can be a live one: a half-written object array
        // would hold stale handles.
        if (p && in.below(2)) {
            std::vector<uint8_t> staged(s->elements * size);
            if (fillElements(in, staged.data(), s->elementType, s->elements, size))
                std::memcpy(p, staged.data(), staged.size());
        }
        anariUnmapArray(device_, array);
    }

    // A parameter of the object's subtype (mostly) or another name, in its listed type (mostly) or another.
    // `listed`: the type is one introspection gives for the name.
    ANARIParameter pickParameter(Input& in, const Slot& s, bool* listed = nullptr) {
        const auto& params = s.subtype ? s.subtype->parameters : std::vector<ANARIParameter>{};
        ANARIParameter p{kExtraNames[0], ANARI_UNKNOWN};
        if (!params.empty() && in.below(8) != 0) p = params[in.below(params.size())];
        else p.name = kExtraNames[in.below(std::size(kExtraNames))];
        const bool keep = p.type != ANARI_UNKNOWN && in.below(4) != 0;
        if (!keep) p.type = kValueTypes[in.below(std::size(kValueTypes))];
        if (listed) *listed = keep;
        return p;
    }

    void setParameter(Input& in) {
        Slot* s = live(in);
        if (!s) return;
        bool listed = false;
        ANARIParameter p = pickParameter(in, *s, &listed);
        alignas(16) uint8_t value[128] = {};
        std::string text;
        if (ripple_anari::isObjectType(p.type) || p.type == ANARI_ARRAY || p.type == ANARI_OBJECT) {
            Slot* v = liveOfType(in, p.type);
            if (!v || (gAvoidWrongHandleType && (!listed || v->type != p.type))) return;
            p.type = v->type;  // the stated type is the handle's own
            std::memcpy(value, &v->handle, sizeof(ANARIObject));
        } else if (p.type == ANARI_STRING) {
            const char** values = nullptr;
            if (s->subtype)
                values = static_cast<const char**>(const_cast<void*>(anariGetParameterInfo(
                    device_, s->type, s->subtype->name.empty() ? nullptr : s->subtype->name.c_str(), p.name,
                    ANARI_STRING, "value", ANARI_STRING_LIST)));
            size_t nValues = 0;
            while (values && values[nValues]) ++nValues;
            if (nValues && in.below(4) != 0) {
                text = values[in.below(nValues)];
            } else {
                text.resize(in.below(12));
                in.fill(text.data(), text.size());
                text = text.c_str();  // the device sees a C string: up to the first NUL
            }
            const char* c = text.c_str();
            std::memcpy(value, &c, sizeof(c));
        } else {
            const size_t size = ripple_anari::sizeOf(p.type);
            if (size == 0 || size > sizeof(value) || p.type == ANARI_VOID_POINTER || p.type == ANARI_STRING_LIST ||
                p.type == ANARI_DATA_TYPE_LIST || p.type == ANARI_PARAMETER_LIST || p.type == ANARI_FUNCTION_POINTER ||
                p.type == ANARI_MEMORY_DELETER || p.type == ANARI_STATUS_CALLBACK ||
                p.type == ANARI_FRAME_COMPLETION_CALLBACK)
                return;  // pointers the fuzzer cannot make meaningful
            in.fill(value, size);
            if (p.type == ANARI_DATA_TYPE && in.below(2)) {
                const ANARIDataType t = kValueTypes[in.below(std::size(kValueTypes))];
                std::memcpy(value, &t, sizeof(t));
            }
        }
        TRACE("set %p '%s' %s\n", (void*)s->handle, p.name, ripple_anari::typeName(p.type));
        anariSetParameter(device_, s->handle, p.name, p.type, value);
    }

    void unsetParameter(Input& in) {
        Slot* s = live(in);
        if (!s) return;
        const ANARIParameter p = pickParameter(in, *s);
        TRACE("unset %p '%s'\n", (void*)s->handle, p.name);
        anariUnsetParameter(device_, s->handle, p.name);
    }

    void mapParameterArray(Input& in) {
        Slot* s = live(in);
        if (!s || !s->subtype || gAvoidMapParameterArray) return;
        const ANARIParameter p = pickParameter(in, *s);
        ANARIDataType type = kValueTypes[in.below(std::size(kValueTypes))];
        if (!ripple_anari::isObjectType(type) && (type == ANARI_STRING || type == ANARI_DATA_TYPE)) type = ANARI_FLOAT32;
        if (ripple_anari::isObjectType(type) || type == ANARI_OBJECT) return;  // handles: see newArray
        const uint64_t count = in.below(16);
        uint64_t stride = 0;
        void* mem = anariMapParameterArray1D(device_, s->handle, p.name, type, count, &stride);
        TRACE("mapParameterArray1D %p '%s' %s x%llu -> %p stride %llu\n", (void*)s->handle, p.name,
              ripple_anari::typeName(type), (unsigned long long)count, mem, (unsigned long long)stride);
        if (!mem) return;
        for (uint64_t e = 0; e < count; ++e) in.fill(static_cast<uint8_t*>(mem) + e * stride, ripple_anari::sizeOf(type));
        anariUnmapParameterArray(device_, s->handle, p.name);
    }

    void getProperty(Input& in) {
        Slot* s = live(in);
        if (!s) return;
        static const char* const names[] = {"bounds", "version", "name", "duration", "channel.color"};
        const char* name = names[in.below(std::size(names))];
        const ANARIDataType type = kValueTypes[in.below(std::size(kValueTypes))];
        const size_t size = ripple_anari::sizeOf(type);
        if (size == 0 || ripple_anari::isObjectType(type) || type == ANARI_STRING) return;
        alignas(16) uint8_t out[128] = {};
        TRACE("getProperty %p '%s' %s\n", (void*)s->handle, name, ripple_anari::typeName(type));
        anariGetProperty(device_, s->handle, name, type, out, size, in.below(2) ? ANARI_WAIT : ANARI_NO_WAIT);
    }

    ANARIDevice device_;
    std::array<Slot, kSlots> slots_{};
};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gVerbose = std::getenv("RIPPLE_FUZZ_VERBOSE") != nullptr;
    const std::string avoid = std::getenv("RIPPLE_FUZZ_AVOID") ? std::getenv("RIPPLE_FUZZ_AVOID") : "";
    gAvoidMapParameterArray = avoid.find("map-parameter-array") != std::string::npos;
    gAvoidWrongHandleType = avoid.find("wrong-handle-type") != std::string::npos;
    gLibrary = anariLoadLibrary("ripple", &statusCallback, nullptr);
    if (!gLibrary) {
        std::fprintf(stderr, "anari fuzzer: cannot load the ripple device library\n");
        std::abort();
    }
    ANARIDevice device = anariNewDevice(gLibrary, "default");
    if (!device) std::abort();
    readIntrospection(device);
    anariRelease(device, device);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    ANARIDevice device = anariNewDevice(gLibrary, "default");
    if (!device) std::abort();
    {
        Input in(data, size);
        Session session(device);
        // Bounded: a long input is many short programs' worth of calls, not a longer run per call.
        for (int steps = 0; steps < 256 && !in.done(); ++steps) session.step(in);
    }
    anariRelease(device, device);
    return 0;
}
