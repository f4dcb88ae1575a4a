// anariLoadLibrary and anariUnloadLibrary of Ripple's libanari.so with the fake device libraries built
// beside this test: where libraries are found, what each failure reports, and the order of unloading.
#include "CallRecord.h"
#include "tests/support/StatusLog.h"

#include "anari/anari.h"

#include <dlfcn.h>
#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

using ripple::test::freshStaticStatusLog;
using ripple::test::StatusLog;

namespace {

// Folders given by CMake: the common lib folder (libanari.so and libanari_library_loadertest.so) and a
// folder that only the "NAME,/dir/" form reaches (libanari_library_elsewhere.so).
const std::string libraryDirectory = LOADERTEST_LIB_DIR;
const std::string elsewhereDirectory = LOADERTEST_ELSEWHERE_DIR;

bool isMapped(const std::string& path) {
    void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_NOLOAD);
    if (handle == nullptr) return false;
    dlclose(handle);  // RTLD_NOLOAD still took a reference
    return true;
}

void checkOneLoadError(StatusLog& log, const char* mentioned) {
    REQUIRE(log.size() == 1);
    CHECK(log.entries[0].severity == ANARI_SEVERITY_ERROR);
    CHECK(log.entries[0].code == ANARI_STATUS_INVALID_ARGUMENT);
    CHECK(log.entries[0].sourceType == ANARI_LIBRARY);
    CHECK_MESSAGE(log.find(mentioned) == 0, log.entries[0].message);
}

}  // namespace

TEST_CASE("A plain name finds the library beside libanari.so") {
    StatusLog& log = freshStaticStatusLog();
    ANARILibrary library = anariLoadLibrary("loadertest", StatusLog::callback, &log);
    REQUIRE(library != nullptr);
    CHECK(log.size() == 0);
    const char** subtypes = anariGetDeviceSubtypes(library);
    REQUIRE(subtypes != nullptr);
    CHECK(std::string(subtypes[0]) == "default");
    CHECK(subtypes[1] == nullptr);
    anariUnloadLibrary(library);
    CHECK(log.errors() == 0);
}

TEST_CASE("\"NAME,/dir/\" names the folder to load from") {
    StatusLog& log = freshStaticStatusLog();
    CHECK(anariLoadLibrary("elsewhere", StatusLog::callback, &log) == nullptr);  // not on any search path
    checkOneLoadError(log, "libanari_library_elsewhere.so");

    for (const std::string& folder : {elsewhereDirectory + "/", elsewhereDirectory}) {
        StatusLog& quiet = freshStaticStatusLog();
        ANARILibrary library = anariLoadLibrary(("elsewhere," + folder).c_str(), StatusLog::callback, &quiet);
        REQUIRE_MESSAGE(library != nullptr, quiet.dump());
        CHECK(quiet.size() == 0);
        anariUnloadLibrary(library);
    }
}

TEST_CASE("\"environment\" takes the name from ANARI_LIBRARY") {
    StatusLog& log = freshStaticStatusLog();
    REQUIRE(setenv("ANARI_LIBRARY", "loadertest", 1) == 0);
    ANARILibrary library = anariLoadLibrary("environment", StatusLog::callback, &log);
    REQUIRE(library != nullptr);
    anariUnloadLibrary(library);

    REQUIRE(setenv("ANARI_LIBRARY", ("elsewhere," + elsewhereDirectory).c_str(), 1) == 0);
    library = anariLoadLibrary("environment", StatusLog::callback, &log);
    REQUIRE(library != nullptr);
    anariUnloadLibrary(library);
    CHECK(log.errors() == 0);

    StatusLog& unsetLog = freshStaticStatusLog();
    REQUIRE(unsetenv("ANARI_LIBRARY") == 0);
    CHECK(anariLoadLibrary("environment", StatusLog::callback, &unsetLog) == nullptr);
    checkOneLoadError(unsetLog, "ANARI_LIBRARY");
}

TEST_CASE("A missing library is reported with every place tried and dlerror's reason") {
    StatusLog& log = freshStaticStatusLog();
    CHECK(anariLoadLibrary("doesnotexist", StatusLog::callback, &log) == nullptr);
    checkOneLoadError(log, "'doesnotexist'");
    CHECK(log.find("libanari_library_doesnotexist.so: cannot open shared object file") == 0);
    CHECK(log.find((libraryDirectory + "/libanari_library_doesnotexist.so").c_str()) == 0);

    // Without a callback the loader still returns NULL (the message goes to stderr).
    CHECK(anariLoadLibrary("doesnotexist", nullptr, nullptr) == nullptr);
}

TEST_CASE("A library without anari_library_NAME_new_library is reported and closed again") {
    StatusLog& log = freshStaticStatusLog();
    // libanari_library_nosymbol.so exports anari_library_wrongname_new_library only.
    CHECK(anariLoadLibrary("nosymbol", StatusLog::callback, &log) == nullptr);
    checkOneLoadError(log, "anari_library_nosymbol_new_library");
    CHECK_FALSE(isMapped(libraryDirectory + "/libanari_library_nosymbol.so"));
}

TEST_CASE("An entry point that returns NULL or throws is reported and closed again") {
    for (const char* failure : {"null", "throw"}) {
        CAPTURE(failure);
        StatusLog& log = freshStaticStatusLog();
        REQUIRE(setenv(loadertest::newLibraryFailureVariable, failure, 1) == 0);
        CHECK(anariLoadLibrary("loadertest", StatusLog::callback, &log) == nullptr);
        REQUIRE(unsetenv(loadertest::newLibraryFailureVariable) == 0);
        checkOneLoadError(log, "anari_library_loadertest_new_library of library 'loadertest' returned NULL");
        CHECK_FALSE(isMapped(libraryDirectory + "/libanari_library_loadertest.so"));
    }
}

TEST_CASE("Names that cannot be libraries are errors, not crashes") {
    for (const char* name : {static_cast<const char*>(nullptr), "", ",/tmp/", "../loadertest"}) {
        CAPTURE(name ? name : "NULL");
        StatusLog& log = freshStaticStatusLog();
        CHECK(anariLoadLibrary(name, StatusLog::callback, &log) == nullptr);
        REQUIRE(log.size() == 1);
        CHECK(log.entries[0].severity == ANARI_SEVERITY_ERROR);
        CHECK(log.entries[0].code == ANARI_STATUS_INVALID_ARGUMENT);
    }
}

TEST_CASE("anariUnloadLibrary deletes the library object, then dlcloses") {
    StatusLog& log = freshStaticStatusLog();
    const std::string path = libraryDirectory + "/libanari_library_loadertest.so";
    ANARILibrary library = anariLoadLibrary("loadertest", StatusLog::callback, &log);
    REQUIRE(library != nullptr);
    CHECK(isMapped(path));
    anariUnloadLibrary(library);
    // The library object reports its destruction, the module its unmapping (an ELF destructor run by
    // dlclose): both must come, in this order.
    const int destroyed = log.find(loadertest::libraryDestroyedMessage);
    const int unmapped = log.find(loadertest::moduleUnmappedMessage);
    CHECK(destroyed == 0);
    CHECK(unmapped == 1);
    CHECK(log.size() == 2);
    CHECK_FALSE(isMapped(path));
}

TEST_CASE("NULL library handles are ignored") {
    anariUnloadLibrary(nullptr);
    anariLoadModule(nullptr, "module");
    anariUnloadModule(nullptr, "module");
    CHECK(anariNewDevice(nullptr, "default") == nullptr);
    CHECK(anariNewInitializedDevice(nullptr, "default", nullptr) == nullptr);
    CHECK(anariGetDeviceSubtypes(nullptr) == nullptr);
    CHECK(anariGetDeviceExtensions(nullptr, "default") == nullptr);
}
