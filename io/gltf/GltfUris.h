// The only way the importer reads a file: the scene file, and the buffer and image files its URIs name,
// confined to one folder (docs/gltf-security.md). Internal to the importer (GltfFile.cpp).
#pragma once

#include "io/FileRead.h"
#include "io/gltf/GltfScene.h"

#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <string>

namespace ripple::apps::gltf {

// The buffer and image URIs of one scene. approve() checks each URI from the JSON before tinygltf sees it;
// callbacks() are the only file access tinygltf gets, and they open only approved files.
class ConfinedUris {
public:
    // Throws GltfError when the scene's folder or options.resourceRoot cannot be resolved.
    ConfinedUris(const std::filesystem::path& sceneFile, const GltfLoadOptions& options, std::string name);
    ConfinedUris(const ConfinedUris&) = delete;
    ConfinedUris& operator=(const ConfinedUris&) = delete;

    // `uri` as the JSON string holds it; `where` is its JSON path ("buffers[0].uri"). data: URIs that tinygltf
    // decodes pass. Throws GltfError naming both for a scheme other than data:, an absolute path, a malformed
    // percent-escape, a path that resolves outside the root, a file that is not regular or is too large.
    // A file that does not exist passes: tinygltf then reports it missing.
    void approve(const std::string& uri, const std::string& where);

    const std::string& baseDir() const { return baseDir_; }  // tinygltf's base directory
    tinygltf::FsCallbacks callbacks();
    // Throws what a callback refused: tinygltf turns a failed image read into a warning.
    void throwIfRefused() const;

private:
    struct Approved {
        std::filesystem::path file;
        std::string label;  // "buffers[0].uri 'a%20b.bin'"
    };
    static bool exists(const std::string& path, void* self);
    static std::string expand(const std::string& path, void* self);
    static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self);
    static bool write(std::string* err, const std::string& path, const std::vector<unsigned char>&, void* self);

    std::string name_;
    uint64_t maxBytes_;
    std::filesystem::path folder_;  // the scene file's folder, canonical
    std::filesystem::path root_;    // canonical; folder_ or options.resourceRoot
    std::string baseDir_;
    std::map<std::string, Approved> approved_;  // by the path tinygltf will ask for
    std::string refused_;
};

}  // namespace ripple::apps::gltf
