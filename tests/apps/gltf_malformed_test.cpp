// Malformed and hostile glTF files, made by the test from a valid one-triangle file with one element
// broken each: every one must end in a GltfError whose message names the file and the broken element.
#include "io/gltf/GltfScene.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <sys/stat.h>

#include <cmath>
#include <limits>
#include <random>

using ripple::apps::GltfError;
using ripple::apps::GltfLoadOptions;
using ripple::apps::loadGltf;
using namespace ripple::test;

namespace {

// The message of the GltfError loading `file` throws; fails the test when it loads or throws anything else.
std::string loadError(const std::filesystem::path& file, const GltfLoadOptions& options = {}) {
    try {
        loadGltf(file, options);
    } catch (const GltfError& e) {
        const std::string message = e.what();
        CHECK_MESSAGE(message.find(file.filename().string()) != std::string::npos, "message does not name the file: " << message);
        return message;
    } catch (const std::exception& e) {
        FAIL("not a GltfError: " << e.what());
    }
    FAIL("loaded without an error: " << file);
    return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("the unbroken triangle loads (the base every malformed case starts from)") {
    TempFolder dir;
    const auto scene = loadGltf(writeGlb(dir / "triangle.glb", triangleSource()));
    CHECK(scene.trianglesStored() == 1);
    CHECK(scene.trianglesDrawn() == 1);
    CHECK(scene.warnings.empty());
}

TEST_CASE("GLB container errors") {
    TempFolder dir;
    const std::vector<uint8_t> good = glbBytes(triangleSource());

    SUBCASE("missing file") { CHECK(contains(loadError(dir / "absent.glb"), "no such file")); }
    SUBCASE("a FIFO as the scene file: refused at once, not waited on") {
        REQUIRE(::mkfifo((dir / "pipe.glb").c_str(), 0600) == 0);
        CHECK(contains(loadError(dir / "pipe.glb"), "pipe.glb: is not a regular file (a FIFO)"));
    }
    SUBCASE("a directory as the scene file") {
        std::filesystem::create_directories(dir / "folder.gltf");
        CHECK(contains(loadError(dir / "folder.gltf"), "folder.gltf: is not a regular file (a directory)"));
    }
    SUBCASE("empty file") {
        CHECK(contains(loadError(writeBytes(dir / "empty.glb", {})), "too short for a GLB header"));
    }
    SUBCASE("truncated in the middle") {
        const std::vector<uint8_t> half(good.begin(), good.begin() + long(good.size() / 2));
        const std::string message = loadError(writeBytes(dir / "truncated.glb", half));
        CHECK(contains(message, "declares " + std::to_string(good.size()) + " bytes but the file has " +
                                    std::to_string(half.size()) + " (truncated?)"));
    }
    SUBCASE("bad magic") {
        std::vector<uint8_t> bytes = good;
        bytes[0] = 'x';
        CHECK(contains(loadError(writeBytes(dir / "magic.glb", bytes)), "bad magic"));
    }
    SUBCASE("chunk length past the end") {
        std::vector<uint8_t> bytes = good;
        bytes[12] = 0xff;  // the JSON chunk's length, little-endian
        bytes[13] = 0xff;
        CHECK(contains(loadError(writeBytes(dir / "chunk.glb", bytes)), "GLB chunk 0"));
    }
}

TEST_CASE("JSON syntax error") {
    TempFolder dir;
    const std::string message = loadError(writeText(dir / "syntax.gltf", R"({"asset":{"version":"2.0"},"nodes":[)"));
    CHECK_MESSAGE(contains(message, "parse error at line 1, column 37"), message);
}

TEST_CASE("buffers that are missing or too short") {
    TempFolder dir;
    SUBCASE("external buffer file missing") {
        GltfSource s = triangleSource();
        s.replace(R"("buffers":[{"byteLength":48}])", R"("buffers":[{"byteLength":48,"uri":"missing.bin"}])");
        const std::string message = loadError(writeText(dir / "external.gltf", s.json));
        CHECK_MESSAGE(contains(message, "File not found : missing.bin"), message);
    }
    SUBCASE("buffer without uri in a .gltf") {
        const std::string message = loadError(writeText(dir / "nouri.gltf", triangleSource().json));
        CHECK(contains(message, "'uri' is missing"));
    }
    SUBCASE("buffer longer than the BIN chunk") {
        GltfSource s = triangleSource();
        s.replace(R"("byteLength":48})", R"("byteLength":480})");
        CHECK(contains(loadError(writeGlb(dir / "short.glb", s)), "byteLength"));
    }
    SUBCASE("buffer view past its buffer") {
        GltfSource s = triangleSource();
        s.replace(R"("byteOffset":36,"byteLength":12)", R"("byteOffset":36,"byteLength":16)");
        CHECK(contains(loadError(writeGlb(dir / "view.glb", s)),
                       "accessor 1 (indices): buffer view 1 (offset 36, length 16) runs past buffer 0 (48 bytes)"));
    }
}

TEST_CASE("accessors that do not fit or have the wrong type") {
    TempFolder dir;
    GltfSource s = triangleSource();
    std::string expected;
    SUBCASE("accessor past its buffer view") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":4,"type":"VEC3")");
        expected = "accessor 0 (POSITION): 4 elements of 12 bytes at offset 0 run past buffer view 0 (36 bytes)";
    }
    SUBCASE("byte offset past its buffer view") {
        s.replace(R"("bufferView":1,"componentType":5125)", R"("bufferView":1,"byteOffset":4,"componentType":5125)");
        expected = "accessor 1 (indices): 3 elements of 4 bytes at offset 4 run past buffer view 1 (12 bytes)";
    }
    SUBCASE("absurd count") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":4000000000,"type":"VEC3")");
        expected = "accessor 0 (POSITION): count 4000000000 is absurd";
    }
    SUBCASE("large count past the buffer") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":100000000,"type":"VEC3")");
        expected = "accessor 0 (POSITION): 100000000 elements of 12 bytes at offset 0 run past buffer view 0";
    }
    SUBCASE("wrong component type for POSITION") {
        s.replace(R"("componentType":5126,"count":3,"type":"VEC3")", R"("componentType":5123,"count":3,"type":"VEC3")");
        expected = "accessor 0 (POSITION) has component type uint16, which glTF does not allow here";
    }
    SUBCASE("wrong type for POSITION") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":3,"type":"VEC2")");
        expected = "accessor 0 (POSITION) has 2 components, expected 3";
    }
    SUBCASE("float indices") {
        s.replace(R"("componentType":5125,"count":3,"type":"SCALAR")", R"("componentType":5126,"count":3,"type":"SCALAR")");
        expected = "accessor 1 (indices) has component type float32, expected uint8, uint16 or uint32";
    }
    SUBCASE("attribute count differs from POSITION") {
        s.replace(R"({"POSITION":0})", R"({"POSITION":0,"NORMAL":2})");
        s.replace(R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}])",
                  R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"},{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"}])");
        expected = "accessor 2 (NORMAL) has 2 elements but POSITION has 3";
    }
    const std::string message = loadError(writeGlb(dir / "accessor.glb", s));
    CHECK_MESSAGE(contains(message, expected), message);
    CHECK(contains(message, "mesh 0 primitive 0"));
}

TEST_CASE("indices and positions with bad values") {
    TempFolder dir;
    GltfSource s = triangleSource();
    std::string expected;
    SUBCASE("index out of range") {
        s.poke(36 + 4, uint32_t(12034));
        expected = "accessor 1 (indices): index 12034 out of range for 3 vertices (element 1)";
    }
    SUBCASE("index count not a multiple of 3") {
        s.replace(R"("componentType":5125,"count":3)", R"("componentType":5125,"count":2)");
        expected = "accessor 1 (indices): count 2 is not a multiple of 3";
    }
    SUBCASE("NaN position") {
        s.poke(4 * 4, std::numeric_limits<float>::quiet_NaN());  // vertex 1, y
        expected = "accessor 0 (POSITION): vertex 1 is not finite";
    }
    SUBCASE("infinite position") {
        s.poke(8 * 4, std::numeric_limits<float>::infinity());  // vertex 2, z
        expected = "accessor 0 (POSITION): vertex 2 is not finite";
    }
    const std::string message = loadError(writeGlb(dir / "values.glb", s));
    CHECK_MESSAGE(contains(message, expected), message);
}

// Dangling indices (a child, mesh, material, scene or accessor that does not exist) are caught on the raw JSON:
// see "indices, offsets and values ..." below.
TEST_CASE("node graphs that are not trees") {
    TempFolder dir;
    GltfSource s = triangleSource();
    std::string expected;
    SUBCASE("cycle") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[1]},{"children":[0]}])");
        expected = "node 0: cycle in the node hierarchy";
    }
    SUBCASE("node that is its own child") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[0]}])");
        expected = "node 0: cycle in the node hierarchy";
    }
    SUBCASE("two parents") {
        s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[1,2]}])");
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0},{"children":[0]},{"children":[0]}])");
        expected = "node 0 is reached twice (it has more than one parent)";
    }
    SUBCASE("over-deep hierarchy") {
        std::string chain;
        for (int i = 0; i < 2000; ++i) chain += R"({"children":[)" + std::to_string(i + 1) + "]},";
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[)" + chain + R"({"mesh":0}])");
        expected = "node hierarchy deeper than 1024 levels";
    }
    SUBCASE("required extension the importer lacks") {
        s.replace(R"("scene":0,)", R"("extensionsRequired":["KHR_draco_mesh_compression"],"extensionsUsed":["KHR_draco_mesh_compression"],"scene":0,)");
        expected = "requires extension KHR_draco_mesh_compression, which this importer does not support";
    }
    SUBCASE("world transform beyond single precision") {
        s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[1]}])");
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"scale":[1e30,1,1]},{"scale":[1e30,1,1],"children":[0]}])");
        expected = "node 0: world transform is not finite in single precision";
    }
    const std::string message = loadError(writeGlb(dir / "nodes.glb", s));
    CHECK_MESSAGE(contains(message, expected), message);
}

TEST_CASE("random corruption never crashes: each of 400 seeded mutations loads or throws GltfError") {
    TempFolder dir;
    GltfSource s = triangleSource();
    s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[1]},{"camera":0,"translation":[0,0,3]}],
        "cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}}])");
    const std::vector<uint8_t> good = glbBytes(s);
    std::mt19937 random(1234);  // fixed seed: the same 400 files on every run
    int loaded = 0, rejected = 0;
    for (int i = 0; i < 400; ++i) {
        std::vector<uint8_t> bytes = good;
        for (int k = 0, n = 1 + int(random() % 6); k < n && !bytes.empty(); ++k) {
            const size_t at = random() % bytes.size();
            switch (random() % 3) {
                case 0: bytes[at] = uint8_t(random()); break;                       // any byte
                case 1: bytes[at] = uint8_t("0123456789-e.,:{}[]\""[random() % 20]); break;  // JSON-ish
                default: bytes.resize(at); break;                                   // truncation
            }
        }
        try {
            loadGltf(writeBytes(dir / "mutant.glb", bytes));
            ++loaded;
        } catch (const GltfError&) {
            ++rejected;
        }  // any other exception escapes and fails the test
    }
    CHECK(loaded + rejected == 400);
    CHECK(rejected > 0);
}

namespace {

// A scene folder dir/scene holding scene.gltf (buffer 0 is the file the test names) and tri.bin, and the
// same triangle bytes outside it, in dir/secret.bin, for URIs that try to climb out.
struct UriFixture {
    TempFolder dir;
    std::filesystem::path folder = dir / "scene";
    GltfSource source = triangleSource();

    UriFixture() {
        std::filesystem::create_directories(folder);
        writeBytes(folder / "tri.bin", source.bin);
        writeBytes(dir / "secret.bin", source.bin);
    }
    std::filesystem::path gltf(const std::string& uri) const {
        GltfSource s = source;
        return writeText(folder / "scene.gltf", s.externalBuffer(uri).json);
    }
};

}  // namespace

TEST_CASE("buffer URIs are confined to the scene's folder") {
    UriFixture f;
    std::string uri, expected;
    GltfLoadOptions options;
    SUBCASE("../ climbing out") {
        uri = "../secret.bin";
        expected = "outside the folder";
    }
    SUBCASE("../ climbing out after a detour") {
        std::filesystem::create_directories(f.folder / "sub");
        uri = "sub/../../secret.bin";
        expected = "outside the folder";
    }
    SUBCASE("absolute path") {
        uri = (f.dir / "secret.bin").string();
        expected = "is an absolute path";
    }
    SUBCASE("absolute path spelt with escapes") {
        uri = "%2Fdev%2Fzero";
        expected = "is an absolute path";
    }
    SUBCASE("/dev/zero") {
        uri = "/dev/zero";
        expected = "is an absolute path";
    }
    SUBCASE("symlink pointing out of the folder") {
        std::filesystem::create_symlink("../secret.bin", f.folder / "link.bin");
        uri = "link.bin";
        expected = "outside the folder";
    }
    SUBCASE("symlink to /dev/zero inside a root widened to /") {
        std::filesystem::create_symlink("/dev/zero", f.folder / "zero.bin");
        uri = "zero.bin";
        options.resourceRoot = "/";
        expected = "is not a regular file (a character device)";
    }
    SUBCASE("FIFO") {
        REQUIRE(::mkfifo((f.folder / "pipe.bin").c_str(), 0600) == 0);
        uri = "pipe.bin";
        expected = "is not a regular file (a FIFO)";
    }
    SUBCASE("directory") {
        std::filesystem::create_directories(f.folder / "sub.bin");
        uri = "sub.bin";
        expected = "is not a regular file (a directory)";
    }
    SUBCASE("file:// scheme") {
        uri = "file://" + (f.folder / "tri.bin").string();
        expected = "the scheme 'file:' is not allowed";
    }
    SUBCASE("http:// scheme") {
        uri = "http://example.com/tri.bin";
        expected = "the scheme 'http:' is not allowed";
    }
    SUBCASE("malformed percent-escape") {
        uri = "tri%2.bin";
        expected = "malformed percent-escape at character 4";
    }
    SUBCASE("percent-escape cut short at the end") {
        uri = "tri.bin%";
        expected = "malformed percent-escape at character 8";
    }
    SUBCASE("escaped NUL byte") {
        uri = "tri.bin%00.txt";
        expected = "decodes to a NUL byte";
    }
    SUBCASE("a file over the 1 GiB limit (sparse, never read)") {
        std::filesystem::path huge = writeBytes(f.folder / "huge.bin", {});
        std::filesystem::resize_file(huge, (uint64_t(1) << 30) + 1);
        uri = "huge.bin";
        expected = "1073741825 bytes is larger than the limit of 1073741824";
    }
    const std::string message = loadError(f.gltf(uri), options);
    CHECK_MESSAGE(contains(message, "buffers[0].uri '" + uri + "': "), message);
    CHECK_MESSAGE(contains(message, expected), message);
}

TEST_CASE("buffer URIs: percent-escapes decoded as RFC 3986 says, and a wider root for trusted input") {
    UriFixture f;
    SUBCASE("my%20file.bin names 'my file.bin'") {
        writeBytes(f.folder / "my file.bin", f.source.bin);
        CHECK(loadGltf(f.gltf("my%20file.bin")).trianglesStored() == 1);
    }
    SUBCASE("'+' is a plus sign, not a space") {
        writeBytes(f.folder / "a+b.bin", f.source.bin);
        CHECK(loadGltf(f.gltf("a+b.bin")).trianglesStored() == 1);
    }
    SUBCASE("escaped sub-folder and ..: allowed while inside the folder") {
        std::filesystem::create_directories(f.folder / "sub dir");
        CHECK(loadGltf(f.gltf("sub%20dir/../tri.bin")).trianglesStored() == 1);
    }
    SUBCASE("JSON escapes are undone before percent-escapes") {
        CHECK(loadGltf(f.gltf(R"(tri\u002Ebin)")).trianglesStored() == 1);
    }
    SUBCASE("symlink inside the folder") {
        std::filesystem::create_symlink("tri.bin", f.folder / "link.bin");
        CHECK(loadGltf(f.gltf("link.bin")).trianglesStored() == 1);
    }
    SUBCASE("a resource root wider than the scene's folder") {
        const std::filesystem::path file = f.gltf("../secret.bin");
        CHECK(contains(loadError(file), "outside the folder"));
        CHECK(loadGltf(file, {.resourceRoot = f.dir / "."}).trianglesStored() == 1);
        CHECK(contains(loadError(file, {.resourceRoot = f.folder}), "outside the folder"));
    }
    SUBCASE("data: URI") {
        // The triangle's 48 bytes in base64.
        const std::string base64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAEAAAACAAAA";
        CHECK(loadGltf(f.gltf("data:application/octet-stream;base64," + base64)).trianglesStored() == 1);
    }
    SUBCASE("data: URI of a media type tinygltf does not decode") {
        const std::string message = loadError(f.gltf("data:text/html,hello"));
        CHECK_MESSAGE(contains(message, "buffers[0].uri 'data:text/html,hello': a data: URI this importer cannot decode"),
                      message);
    }
}

TEST_CASE("image URIs are confined like buffer URIs") {
    UriFixture f;
    GltfSource s = triangleSource();
    s.replace(R"("buffers":)", R"("images":[{"uri":"../secret.png"}],"buffers":)");
    const std::string message = loadError(writeGlb(f.folder / "image.glb", s));
    CHECK_MESSAGE(contains(message, "images[0].uri '../secret.png': "), message);
    CHECK_MESSAGE(contains(message, "outside the folder"), message);
}

TEST_CASE("JSON nesting is bounded before parsing") {
    TempFolder dir;
    GltfSource s = triangleSource();
    const int levels = 20000;
    SUBCASE("20,000 levels of arrays in a .glb") {
        s.replace(R"("scene":0,)", R"("extras":)" + std::string(levels, '[') + std::string(levels, ']') + ",\"scene\":0,");
        const std::string message = loadError(writeGlb(dir / "deep.glb", s));
        CHECK_MESSAGE(contains(message, "JSON nested 20001 levels deep, over the limit of 512"), message);
    }
    SUBCASE("20,000 levels of objects in a .gltf") {
        std::string deep;
        for (int i = 0; i < levels; ++i) deep += R"({"a":)";
        deep += "0" + std::string(levels, '}');
        const std::string message = loadError(writeText(dir / "deep.gltf", R"({"asset":{"version":"2.0"},"extras":)" + deep + "}"));
        CHECK_MESSAGE(contains(message, "JSON nested 20001 levels deep, over the limit of 512"), message);
    }
    SUBCASE("brackets inside strings, escaped quotes included, do not count") {
        const std::string brackets(2000, '[');
        s.replace(R"("scene":0,)", R"("extras":{"a":"\")" + brackets + R"(","b\"[":"[[[\\"},"scene":0,)");
        CHECK(loadGltf(writeGlb(dir / "strings.glb", s)).trianglesStored() == 1);
    }
    SUBCASE("exactly at the limit loads") {
        s.replace(R"("scene":0,)", R"("extras":)" + std::string(511, '[') + std::string(511, ']') + ",\"scene\":0,");
        CHECK(loadGltf(writeGlb(dir / "limit.glb", s)).trianglesStored() == 1);
    }
}

TEST_CASE("not a glTF file: JSON that is not an object with an 'asset'") {
    TempFolder dir;
    SUBCASE("{}") {
        const std::string message = loadError(writeText(dir / "empty.gltf", "{}"));
        CHECK_MESSAGE(contains(message, "not a glTF file: no 'asset' object"), message);
    }
    SUBCASE("42") {
        const std::string message = loadError(writeText(dir / "number.gltf", "42"));
        CHECK_MESSAGE(contains(message, "not a glTF file: the JSON is a number, not an object"), message);
    }
    SUBCASE("42 in a .glb") {
        GltfSource s;
        s.json = "42";
        const std::string message = loadError(writeGlb(dir / "number.glb", s));
        CHECK_MESSAGE(contains(message, "not a glTF file: the JSON is a number, not an object"), message);
    }
    SUBCASE("'asset' that is not an object") {
        const std::string message = loadError(writeText(dir / "asset.gltf", R"({"asset":"2.0"})"));
        CHECK_MESSAGE(contains(message, "not a glTF file: 'asset' is a string, not an object"), message);
    }
}

TEST_CASE("indices, offsets and values tinygltf would coerce or drop: errors name the JSON path") {
    TempFolder dir;
    GltfSource s = triangleSource();
    std::string expected;
    SUBCASE("mesh index past the mesh count") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":5}])");
        expected = "nodes[0].mesh: 5 is out of range (the file has 1 meshes)";
    }
    SUBCASE("mesh index 1.5") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":1.5}])");
        expected = "nodes[0].mesh: expected an integer, found 1.5";
    }
    SUBCASE("mesh index \"0\"") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":"0"}])");
        expected = "nodes[0].mesh: expected an integer, found a string";
    }
    SUBCASE("mesh index -1") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":-1}])");
        expected = "nodes[0].mesh: -1 is out of range (the file has 1 meshes)";
    }
    SUBCASE("mesh index 2^32 (an int cast would make it 0)") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":4294967296}])");
        expected = "nodes[0].mesh: 4294967296 is out of range (the file has 1 meshes)";
    }
    SUBCASE("child index past the node count") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[7]}])");
        expected = "nodes[0].children[0]: 7 is out of range (the file has 1 nodes)";
    }
    SUBCASE("scene root 1.0") {
        s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[1.0]}])");
        expected = "scenes[0].nodes[0]: expected an integer, found 1.0";
    }
    SUBCASE("default scene past the scene count") {
        s.replace(R"("scene":0)", R"("scene":4)");
        expected = "scene: 4 is out of range (the file has 1 scenes)";
    }
    SUBCASE("material index past the material count") {
        s.replace(R"("indices":1})", R"("indices":1,"material":3})");
        expected = "meshes[0].primitives[0].material: 3 is out of range (the file has 0 materials)";
    }
    SUBCASE("indices accessor past the accessor count") {
        s.replace(R"("indices":1)", R"("indices":9)");
        expected = "meshes[0].primitives[0].indices: 9 is out of range (the file has 2 accessors)";
    }
    SUBCASE("attribute accessor past the accessor count") {
        s.replace(R"({"POSITION":0})", R"({"POSITION":0,"TEXCOORD_0":9})");
        expected = "meshes[0].primitives[0].attributes.TEXCOORD_0: 9 is out of range (the file has 2 accessors)";
    }
    SUBCASE("accessor count given as a string") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":"3","type":"VEC3")");
        expected = "accessors[0].count: expected an integer, found a string";
    }
    SUBCASE("negative bufferView byteOffset") {
        s.replace(R"("byteOffset":36,"byteLength":12)", R"("byteOffset":-4,"byteLength":12)");
        expected = "bufferViews[1].byteOffset: -4 is negative";
    }
    SUBCASE("negative accessor byteOffset") {
        s.replace(R"("bufferView":1,"componentType":5125)", R"("bufferView":1,"byteOffset":-4,"componentType":5125)");
        expected = "accessors[1].byteOffset: -4 is negative";
    }
    SUBCASE("accessor byteOffset misaligned for its component type") {
        s.replace(R"("bufferView":1,"componentType":5125)", R"("bufferView":1,"byteOffset":2,"componentType":5125)");
        expected = "accessors[1].byteOffset: 2 plus bufferViews[1].byteOffset 36 is 38, not a multiple of the "
                   "component size 4";
    }
    SUBCASE("bufferView byteOffset misaligned for its accessor's component type") {
        s.bin.insert(s.bin.begin() + 36, {0, 0});
        s.replace(R"("buffers":[{"byteLength":48}])", R"("buffers":[{"byteLength":50}])");
        s.replace(R"("byteOffset":36,"byteLength":12)", R"("byteOffset":38,"byteLength":12)");
        expected = "accessors[1].byteOffset: 0 plus bufferViews[1].byteOffset 38 is 38, not a multiple of the "
                   "component size 4";
    }
    SUBCASE("stride below the element size") {
        s.replace(R"({"buffer":0,"byteOffset":0,"byteLength":36})", R"({"buffer":0,"byteOffset":0,"byteLength":36,"byteStride":4})");
        expected = "accessors[0] (bufferView 0): byteStride 4 is smaller than the element size 12";
    }
    SUBCASE("camera aspectRatio 0") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"camera":0}],
            "cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1,"aspectRatio":0}}])");
        expected = "cameras[0].perspective.aspectRatio: must be greater than 0, found 0";
    }
    SUBCASE("negative light range") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"extensions":{"KHR_lights_punctual":{"light":0}}}],
            "extensionsUsed":["KHR_lights_punctual"],
            "extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","range":-1}]}})");
        expected = "extensions.KHR_lights_punctual.lights[0].range: must be greater than 0, found -1";
    }
    SUBCASE("light index past the light count") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"extensions":{"KHR_lights_punctual":{"light":3}}}],
            "extensionsUsed":["KHR_lights_punctual"],
            "extensions":{"KHR_lights_punctual":{"lights":[{"type":"point"}]}})");
        expected = "nodes[0].extensions.KHR_lights_punctual.light: 3 is out of range (the file has 1 lights)";
    }
    const std::string message = loadError(writeGlb(dir / "paths.glb", s));
    CHECK_MESSAGE(contains(message, expected), message);
}
