// Reads a .gltf or .glb into a tinygltf::Model. Before tinygltf sees the file: the GLB container (its own
// checks let a chunk header run a few bytes past the data), the JSON's nesting depth, the raw JSON's indices
// and offsets, and every URI. Images stored in buffer views are decoded only after their range is checked.
#include "io/gltf/GltfFile.h"

#include "io/gltf/GltfJson.h"
#include "io/gltf/GltfJsonChecks.h"
#include "io/gltf/GltfUris.h"

#include <stb_image.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <string_view>

namespace ripple::apps::gltf {

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;      // "BIN\0"

uint32_t readLittle32(const std::string& bytes, size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;  // glTF is little-endian, as is every machine Ripple builds for
}

// Walks the GLB header and chunks; every length must stay inside the file. Returns the JSON chunk.
std::string_view checkGlbContainer(const std::string& bytes, const std::string& name) {
    if (bytes.size() < 12)
        throw GltfError(name + ": " + std::to_string(bytes.size()) + " bytes is too short for a GLB header");
    if (readLittle32(bytes, 0) != kGlbMagic)
        throw GltfError(name + ": bad magic, not a GLB file (the first 4 bytes are not 'glTF')");
    if (const uint32_t version = readLittle32(bytes, 4); version != 2)
        throw GltfError(name + ": GLB version " + std::to_string(version) + ", expected 2");
    const uint64_t length = readLittle32(bytes, 8);
    if (length > bytes.size())
        throw GltfError(name + ": the GLB header declares " + std::to_string(length) + " bytes but the file has " +
                        std::to_string(bytes.size()) + " (truncated?)");
    uint64_t at = 12;
    std::string_view json;
    for (int chunk = 0; at < length; ++chunk) {
        if (length - at < 8)
            throw GltfError(name + ": GLB chunk " + std::to_string(chunk) + " header at byte " + std::to_string(at) +
                            " runs past the end of the file");
        const uint64_t chunkLength = readLittle32(bytes, size_t(at));
        const uint32_t type = readLittle32(bytes, size_t(at) + 4);
        if (chunkLength > length - at - 8)
            throw GltfError(name + ": GLB chunk " + std::to_string(chunk) + " of " + std::to_string(chunkLength) +
                            " bytes at byte " + std::to_string(at) + " runs past the end of the file (" +
                            std::to_string(length) + " bytes; truncated?)");
        if (chunk == 0 && type != kChunkJson) throw GltfError(name + ": the first GLB chunk is not JSON");
        if (chunk == 0) json = std::string_view(bytes).substr(size_t(at) + 8, size_t(chunkLength));
        if (chunk == 1 && type != kChunkBin) throw GltfError(name + ": the second GLB chunk is not BIN");
        at += 8 + chunkLength;
    }
    if (at == 12) throw GltfError(name + ": the GLB file has no JSON chunk");
    return json;
}

// Shared with tinygltf's image callback.
struct ImageDecoding {
    const GltfLoadOptions* options = nullptr;
    std::vector<std::string>* warnings = nullptr;
    std::string fatal;   // set when an image must stop the load (too large to allocate)
};

// Decodes an encoded image (PNG, JPEG, ...) into `image` as RGBA8. A format stb cannot read is a warning;
// an absurd size is fatal.
bool decodeInto(tinygltf::Image& image, int index, const unsigned char* bytes, size_t size, ImageDecoding& ctx) {
    const std::string name = "image " + std::to_string(index);
    if (size == 0 || size > size_t(INT32_MAX)) {
        ctx.warnings->push_back(name + ": no encoded data; left empty");
        return true;
    }
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, int(size), &w, &h, &comp)) {
        ctx.warnings->push_back(name + " (" + image.mimeType + "): cannot decode (" + stbi_failure_reason() +
                                "); left empty");
        return true;
    }
    if (w <= 0 || h <= 0 || uint64_t(w) * uint64_t(h) > ctx.options->maxImagePixels) {
        ctx.fatal = name + ": " + std::to_string(w) + "x" + std::to_string(h) + " pixels is over the limit of " +
                    std::to_string(ctx.options->maxImagePixels);
        return false;
    }
    unsigned char* pixels = stbi_load_from_memory(bytes, int(size), &w, &h, &comp, 4);
    if (!pixels) {
        ctx.warnings->push_back(name + ": cannot decode (" + std::string(stbi_failure_reason()) + "); left empty");
        return true;
    }
    image.width = w;
    image.height = h;
    image.component = 4;
    image.bits = 8;
    image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image.image.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
    stbi_image_free(pixels);
    return true;
}

// tinygltf calls this for every image. Images in a buffer view are left for later: tinygltf hands over a
// pointer computed from an unchecked offset. Images from a file or a data URI arrive as checked bytes.
bool onImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
             const unsigned char* bytes, int size, void* user) {
    auto& ctx = *static_cast<ImageDecoding*>(user);
    if (!ctx.options->decodeImages || image->bufferView >= 0) return true;
    const bool ok = decodeInto(*image, index, bytes, size_t(std::max(size, 0)), ctx);
    if (!ok && err) *err += ctx.fatal;
    return ok;
}

void decodeBufferViewImages(tinygltf::Model& model, ImageDecoding& ctx, const std::string& name) {
    for (size_t i = 0; i < model.images.size(); ++i) {
        tinygltf::Image& image = model.images[i];
        if (image.bufferView < 0) continue;
        const std::string what = name + ": image " + std::to_string(i);
        if (size_t(image.bufferView) >= model.bufferViews.size())
            throw GltfError(what + ": buffer view " + std::to_string(image.bufferView) + " does not exist");
        const tinygltf::BufferView& view = model.bufferViews[size_t(image.bufferView)];
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
            throw GltfError(what + ": buffer " + std::to_string(view.buffer) + " does not exist");
        const std::vector<unsigned char>& data = model.buffers[size_t(view.buffer)].data;
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
            throw GltfError(what + ": buffer view " + std::to_string(image.bufferView) + " runs past buffer " +
                            std::to_string(view.buffer));
        if (!decodeInto(image, int(i), data.data() + view.byteOffset, view.byteLength, ctx))
            throw GltfError(name + ": " + ctx.fatal);
    }
}

}  // namespace

void parseFile(const std::filesystem::path& file, const GltfLoadOptions& options, tinygltf::Model& model,
               std::vector<std::string>& warnings) {
    const std::string name = file.string();
    std::string bytes, readError;
    if (!readRegularFile(file, options.maxFileBytes, false, bytes, readError)) throw GltfError(name + ": " + readError);
    const bool binary = (bytes.size() >= 4 && readLittle32(bytes, 0) == kGlbMagic) || file.extension() == ".glb";
    const std::string_view json = binary ? checkGlbContainer(bytes, name) : std::string_view(bytes);

    // Before any parser: they recurse once per level, and some tens of kilobytes of brackets overflowed the stack.
    if (const uint32_t depth = jsonNestingDepth(json); depth > options.maxJsonDepth)
        throw GltfError(name + ": JSON nested " + std::to_string(depth) + " levels deep, over the limit of " +
                        std::to_string(options.maxJsonDepth) + " (arrays and objects)");
    ConfinedUris uris(file, options, name);
    std::string syntaxError;
    const std::optional<Json> root = parseJson(json, syntaxError);
    if (root) {
        checkGltfJson(*root, name);  // buffers and images are arrays of objects, each uri a string
        for (const char* collection : {"buffers", "images"})
            if (const Json* items = jsonMember(*root, collection))
                for (size_t i = 0; i < items->size(); ++i)
                    if (const Json* uri = jsonMember((*items)[i], "uri"))
                        uris.approve(uri->get_ref<const std::string&>(),
                                     std::string(collection) + "[" + std::to_string(i) + "].uri");
    }  // else tinygltf reports the syntax error in its words below; with no URI approved it can open no file

    ImageDecoding ctx{&options, &warnings, {}};
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(onImage, &ctx);
    loader.SetFsCallbacks(uris.callbacks());
    std::string error, warning;
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                                  reinterpret_cast<const unsigned char*>(bytes.data()),
                                                  unsigned(bytes.size()), uris.baseDir())
                    : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(), unsigned(bytes.size()),
                                                 uris.baseDir());
    } catch (const std::exception& e) {  // tinygltf throws from a few unchecked container accesses
        throw GltfError(name + ": " + e.what());
    }
    uris.throwIfRefused();
    auto trim = [](std::string s) {
        while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
        return s;
    };
    if (!ok) throw GltfError(name + ": " + (error.empty() ? "tinygltf could not parse it" : trim(error)));
    if (!root) throw GltfError(name + ": JSON " + syntaxError);  // "JSON parse error at line 1, column 37: ..."
    if (!warning.empty()) warnings.push_back(trim(warning));
    if (options.decodeImages) decodeBufferViewImages(model, ctx, name);
}

}  // namespace ripple::apps::gltf
