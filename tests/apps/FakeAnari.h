// A recording stand-in for the ANARI C API, linked into the apps suite in place of the loader: it keeps every
// object the scene builders create, with its parameters and array contents, so tests can check what an
// application hands a device without any device.
#pragma once

#include <anari/anari.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace ripple::test {

struct FakeObject;

struct FakeParameter {
    ANARIDataType type = ANARI_UNKNOWN;
    std::vector<uint8_t> bytes;        // the value, for plain data types
    std::string text;                  // ANARI_STRING
    FakeObject* object = nullptr;      // handle types

    template <typename T>
    T as() const;                      // the value's bytes as T (sizes must match)
};

struct FakeObject {
    ANARIDataType type = ANARI_UNKNOWN;
    std::string subtype;               // empty for surfaces, groups, worlds, arrays
    std::map<std::string, FakeParameter> parameters;
    bool committed = false;
    int appReferences = 1;             // the creator's reference; anariRelease takes it
    // Arrays
    ANARIDataType elementType = ANARI_UNKNOWN;
    uint64_t count1 = 0, count2 = 1;
    std::vector<uint8_t> data;

    template <typename T>
    const T* elements() const { return reinterpret_cast<const T*>(data.data()); }
};

struct FakeDevice {
    std::vector<std::unique_ptr<FakeObject>> objects;
    std::vector<std::string> misuse;   // API misuse seen (use after release, double release, ...)

    std::vector<const FakeObject*> ofType(ANARIDataType type, const std::string& subtype = "*") const;
};

// A fresh fake device; the previous one (and all its objects) is discarded.
ANARIDevice newFakeDevice();
FakeDevice& fakeDevice();
const FakeObject* fakeObject(ANARIObject handle);

template <typename T>
T FakeParameter::as() const {
    T value{};
    if (bytes.size() == sizeof(T)) std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
}

}  // namespace ripple::test
