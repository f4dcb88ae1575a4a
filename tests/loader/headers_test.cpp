// The enum values and handle types of Ripple's ANARI headers against ANARI.md section 2, and the helpers
// of anari_type_traits.hpp. Values are exact; counts cover every constant of the standard.
#include "anari/anari.h"
#include "anari/anari_type_traits.hpp"

#include <doctest/doctest.h>

#include <string>
#include <type_traits>

extern "C" int loadertestCHeaderValues(void);

using namespace ripple_anari;

TEST_CASE("Enum values match the ANARI 1.0 standard") {
    CHECK(ANARI_UNKNOWN == 0);
    CHECK(ANARI_BOOL == 103);
    CHECK(ANARI_FRAME_COMPLETION_CALLBACK == 203);
    CHECK(ANARI_LIBRARY == 500);
    CHECK(ANARI_WORLD == 519);
    CHECK(ANARI_FLOAT32_VEC3 == 1070);
    CHECK(ANARI_UINT32_VEC3 == 1022);
    CHECK(ANARI_UFIXED8_VEC4 == 1039);
    CHECK(ANARI_FLOAT64_VEC4 == 1075);
    CHECK(ANARI_UFIXED8_RGBA_SRGB == 2003);
    CHECK(ANARI_FLOAT32_BOX3 == 2010);
    CHECK(ANARI_FLOAT32_MAT3x4 == 2016);
    CHECK(ANARI_FLOAT32_QUAT_IJKW == 2017);
    CHECK(ANARI_UINT64_REGION4 == 2107);
    CHECK(ANARI_FLOAT64_BOX1 == 2208);
    CHECK(ANARI_WAIT == 1);
    CHECK(ANARI_NO_WAIT == 0);
    CHECK(ANARI_SEVERITY_FATAL_ERROR == 1);
    CHECK(ANARI_SEVERITY_DEBUG == 6);
    CHECK(ANARI_STATUS_INVALID_ARGUMENT == 2);
    CHECK(ANARI_STATUS_VERSION_MISMATCH == 6);
    CHECK(loadertestCHeaderValues() == 1071);
}

TEST_CASE("Every data type constant has a name and a size") {
    int named = 0;
    int objects = 0;
    for (int type = 1; type < 3000; ++type) {
        if (std::string(typeName(type)) == "ANARI_UNKNOWN") {
            CHECK_MESSAGE(sizeOf(type) == 0, type);
            continue;
        }
        ++named;
        CHECK_MESSAGE(sizeOf(type) > 0, typeName(type));
        objects += isObjectType(type) ? 1 : 0;
    }
    // 7 (100-103, 150-152) + 4 (200-203) + 20 handles + 76 numeric + 4 sRGB + 12 boxes (INT32, FLOAT32,
    // FLOAT64) + 5 matrices and the quaternion + 4 regions; ANARI_UNKNOWN is not counted.
    CHECK(named == 7 + 4 + 20 + 76 + 4 + 12 + 6 + 4);
    CHECK(objects == 19);  // ANARI_DEVICE .. ANARI_WORLD; a library is not an object
    CHECK(std::string(typeName(ANARI_FLOAT32_VEC3)) == "ANARI_FLOAT32_VEC3");
    CHECK(std::string(typeName(ANARI_UNKNOWN)) == "ANARI_UNKNOWN");
    CHECK(std::string(typeName(-5)) == "ANARI_UNKNOWN");
}

TEST_CASE("Element sizes in bytes") {
    CHECK(sizeOf(ANARI_UINT8) == 1);
    CHECK(sizeOf(ANARI_UFIXED8_VEC4) == 4);
    CHECK(sizeOf(ANARI_FLOAT16_VEC3) == 6);
    CHECK(sizeOf(ANARI_INT32_VEC2) == 8);
    CHECK(sizeOf(ANARI_FLOAT32_VEC3) == 12);
    CHECK(sizeOf(ANARI_UFIXED32_VEC3) == 12);
    CHECK(sizeOf(ANARI_FLOAT64_VEC4) == 32);
    CHECK(sizeOf(ANARI_UINT64_VEC2) == 16);
    CHECK(sizeOf(ANARI_BOOL) == 4);
    CHECK(sizeOf(ANARI_DATA_TYPE) == 4);
    CHECK(sizeOf(ANARI_STRING) == sizeof(char*));
    CHECK(sizeOf(ANARI_ARRAY1D) == sizeof(void*));
    CHECK(sizeOf(ANARI_UFIXED8_RGB_SRGB) == 3);
    CHECK(sizeOf(ANARI_INT32_BOX1) == 8);
    CHECK(sizeOf(ANARI_FLOAT32_BOX3) == 24);
    CHECK(sizeOf(ANARI_FLOAT64_BOX3) == 48);
    CHECK(sizeOf(ANARI_UINT64_REGION2) == 32);
    CHECK(sizeOf(ANARI_FLOAT32_MAT3) == 36);
    CHECK(sizeOf(ANARI_FLOAT32_MAT4) == 64);
    CHECK(sizeOf(ANARI_FLOAT32_MAT3x4) == 48);
    CHECK(sizeOf(ANARI_FLOAT32_QUAT_IJKW) == 16);
    static_assert(sizeOf(ANARI_FLOAT32_VEC3) == 12, "usable in constant expressions");
}

TEST_CASE("typeOf and isObjectType") {
    static_assert(typeOf<float>() == ANARI_FLOAT32);
    static_assert(typeOf<double>() == ANARI_FLOAT64);
    static_assert(typeOf<int32_t>() == ANARI_INT32);
    static_assert(typeOf<uint32_t>() == ANARI_UINT32);
    static_assert(typeOf<uint64_t>() == ANARI_UINT64);
    static_assert(typeOf<uint8_t>() == ANARI_UINT8);
    static_assert(typeOf<bool>() == ANARI_BOOL);
    CHECK(isObjectType(ANARI_DEVICE));
    CHECK(isObjectType(ANARI_WORLD));
    CHECK_FALSE(isObjectType(ANARI_LIBRARY));
    CHECK_FALSE(isObjectType(ANARI_FLOAT32));
}

TEST_CASE("Handles convert to their bases only, as with the Khronos header") {
    static_assert(std::is_convertible_v<ANARIArray1D, ANARIArray>);
    static_assert(std::is_convertible_v<ANARIArray1D, ANARIObject>);
    static_assert(std::is_convertible_v<ANARIGeometry, ANARIObject>);
    static_assert(std::is_convertible_v<ANARIDevice, ANARIObject>);
    static_assert(!std::is_convertible_v<ANARIObject, ANARIArray1D>);
    static_assert(!std::is_convertible_v<ANARIGeometry, ANARIArray>);
    static_assert(!std::is_convertible_v<ANARILibrary, ANARIObject>);
    static_assert(!std::is_same_v<ANARIArray2D, ANARIArray3D>);
    CHECK(true);
}
