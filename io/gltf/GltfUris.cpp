// URI rules of the glTF specification (RFC 3986 references: percent-escapes, no '+' for space) plus the
// importer's confinement. tinygltf decodes URIs its own way ('+' as space, bad escapes as NUL) before it
// calls the file callbacks, so approved files are looked up by the path tinygltf will build, not re-derived.
#include "io/gltf/GltfUris.h"

#include "io/FileRead.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>

namespace ripple::apps::gltf {

namespace {

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// What tinygltf 2.7 makes of a URI before it asks for the file (its urldecode). Only called on URIs whose
// escapes are all well formed, where the two decodings differ in '+' alone.
std::string tinygltfDecoded(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && i + 2 < uri.size()) {
            out += char(hexValue(uri[i + 1]) * 16 + hexValue(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// tinygltf's JoinPath.
std::string joinPath(const std::string& dir, const std::string& file) {
    if (dir.empty()) return file;
    return dir.back() == '/' ? dir + file : dir + "/" + file;
}

bool startsWithNoCase(const std::string& s, const char* prefix) {
    const size_t n = std::strlen(prefix);
    return s.size() >= n && strncasecmp(s.c_str(), prefix, n) == 0;
}


}  // namespace

ConfinedUris::ConfinedUris(const std::filesystem::path& sceneFile, const GltfLoadOptions& options, std::string name)
    : name_(std::move(name)), maxBytes_(options.maxFileBytes), baseDir_(sceneFile.parent_path().string()) {
    std::error_code ec;
    folder_ = std::filesystem::canonical(std::filesystem::absolute(sceneFile, ec).parent_path(), ec);
    if (ec) throw GltfError(name_ + ": cannot resolve the file's folder: " + ec.message());
    root_ = folder_;
    if (!options.resourceRoot.empty()) {
        root_ = std::filesystem::canonical(options.resourceRoot, ec);
        if (ec) throw GltfError(name_ + ": resource root " + options.resourceRoot.string() + ": " + ec.message());
    }
}

void ConfinedUris::approve(const std::string& uri, const std::string& where) {
    const std::string label = where + " '" + uri + "'";
    const auto fail = [&](const std::string& what) { throw GltfError(name_ + ": " + label + ": " + what); };
    if (startsWithNoCase(uri, "data:")) {
        if (!tinygltf::IsDataURI(uri))
            fail("a data: URI this importer cannot decode (it reads base64 data of the media types glTF uses)");
        return;
    }
    // RFC 3986: a scheme is a letter, then letters, digits, '+', '-' or '.', then ':'.
    size_t schemeEnd = 0;
    if (!uri.empty() && std::isalpha(static_cast<unsigned char>(uri[0]))) {
        schemeEnd = 1;
        while (schemeEnd < uri.size() && (std::isalnum(static_cast<unsigned char>(uri[schemeEnd])) ||
                                          std::strchr("+-.", uri[schemeEnd])))
            ++schemeEnd;
        if (schemeEnd < uri.size() && uri[schemeEnd] == ':')
            fail("the scheme '" + uri.substr(0, schemeEnd + 1) + "' is not allowed (only data: URIs and relative paths)");
    }
    if (uri.find_first_of("?#") != std::string::npos)
        fail("has a query or fragment ('?' or '#'), which names no file (a file name with them spells them %3F, %23)");

    std::string path;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] != '%') {
            path += uri[i];
            continue;
        }
        if (i + 2 >= uri.size() || hexValue(uri[i + 1]) < 0 || hexValue(uri[i + 2]) < 0)
            fail("malformed percent-escape at character " + std::to_string(i + 1) + " (expected '%' and two hex digits)");
        const char c = char(hexValue(uri[i + 1]) * 16 + hexValue(uri[i + 2]));
        if (c == '\0') fail("decodes to a NUL byte");
        path += c;
        i += 2;
    }
    if (path.empty()) fail("is empty");
    if (path[0] == '/') fail("is an absolute path (only paths relative to the scene file's folder are allowed)");

    std::error_code ec;
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(folder_ / path, ec);
    if (ec) fail("cannot be resolved: " + ec.message());
    if (!pathInside(root_, resolved))
        fail("resolves to " + resolved.string() + ", outside the folder " + root_.string() +
             " that URIs are confined to");
    struct stat st {};
    if (::stat(resolved.c_str(), &st) == 0) {  // a missing file is tinygltf's to report
        if (!S_ISREG(st.st_mode)) fail(std::string("is not a regular file (") + fileKindName(st.st_mode) + ")");
        if (uint64_t(st.st_size) > maxBytes_) fail(tooLargeReason(uint64_t(st.st_size), maxBytes_));
    }

    const std::string key = joinPath(baseDir_, tinygltfDecoded(uri));
    const auto [it, added] = approved_.emplace(key, Approved{resolved, label});
    if (!added && it->second.file != resolved)
        fail("tinygltf cannot tell it from " + it->second.label + " (it reads '+' as a space); escape '+' as %2B");
}

bool ConfinedUris::exists(const std::string& path, void* self) {
    const auto& uris = *static_cast<ConfinedUris*>(self);
    const auto it = uris.approved_.find(path);
    struct stat st {};
    return it != uris.approved_.end() && ::stat(it->second.file.c_str(), &st) == 0;
}

std::string ConfinedUris::expand(const std::string& path, void*) {
    return path;  // never expanded: the path is the key of an approved file (some tinygltf versions ran wordexp)
}

bool ConfinedUris::read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self) {
    auto& uris = *static_cast<ConfinedUris*>(self);
    const auto it = uris.approved_.find(path);
    std::string error;
    if (it == uris.approved_.end()) error = path + ": not a file this importer approved";
    else if (readRegularFile(it->second.file, uris.maxBytes_, true, *out, error)) return true;
    else error = it->second.label + ": " + error;
    if (uris.refused_.empty()) uris.refused_ = error;
    if (err) *err += error;
    return false;
}

bool ConfinedUris::write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the importer writes no files";
    return false;
}

tinygltf::FsCallbacks ConfinedUris::callbacks() { return {&exists, &expand, &read, &write, this}; }

void ConfinedUris::throwIfRefused() const {
    if (!refused_.empty()) throw GltfError(name_ + ": " + refused_);
}

}  // namespace ripple::apps::gltf
