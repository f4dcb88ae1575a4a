// glTF -> GltfScene: tinygltf parses (GltfFile.cpp), this file checks every index it follows and flattens the
// node tree into world transforms, keeping meshes shared between the nodes that draw them.
#include "io/gltf/GltfScene.h"

#include "io/gltf/GltfAccessors.h"
#include "io/gltf/GltfFile.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

namespace ripple::apps {

uint64_t GltfScene::trianglesStored() const {
    uint64_t total = 0;
    for (const GltfGeometry& g : geometries) total += g.indices.size();
    return total;
}

uint64_t GltfScene::trianglesDrawn() const {
    std::vector<uint64_t> perMesh(meshes.size(), 0);
    for (size_t m = 0; m < meshes.size(); ++m)
        for (const GltfPrimitive& p : meshes[m].primitives) perMesh[m] += geometries[p.geometry].indices.size();
    uint64_t total = 0;
    for (const GltfMeshInstance& instance : instances) total += perMesh[instance.mesh];
    return total;
}

namespace {

bool allFinite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

template <typename Vec>
size_t firstNonFinite(const std::vector<Vec>& values) {
    for (size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < Vec::length(); ++c)
            if (!std::isfinite(values[i][c])) return i;
    return values.size();
}

class Converter {
public:
    // Takes `model` by mutable reference only to move decoded pixels out of it.
    Converter(tinygltf::Model& model, const GltfLoadOptions& options, GltfScene& scene)
        : model_(model), options_(options), scene_(scene), name_(scene.file.string()) {}

    void run() {
        requiredExtensions();
        images();
        textures();
        materials();
        meshes();
        nodes();
        bounds();
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw GltfError(name_ + ": " + what); }
    void warn(const std::string& what) { scene_.warnings.push_back(what); }

    // A file may only be read by importers that know every extension it requires (compressed or quantized
    // geometry would otherwise load as garbage).
    void requiredExtensions() const {
        static const char* const supported[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};
        for (const std::string& name : model_.extensionsRequired)
            if (std::find(std::begin(supported), std::end(supported), name) == std::end(supported))
                fail("requires extension " + name + ", which this importer does not support");
    }

    void images() {
        for (size_t i = 0; i < model_.images.size(); ++i) {
            tinygltf::Image& src = model_.images[i];
            GltfImage& image = scene_.images.emplace_back();
            image.name = src.name;
            // Only the decoder of GltfFile.cpp fills pixels, always as RGBA8; anything else stays empty.
            if (src.component == 4 && src.bits == 8 && src.width > 0 && src.height > 0 &&
                src.image.size() == size_t(src.width) * size_t(src.height) * 4) {
                image.width = uint32_t(src.width);
                image.height = uint32_t(src.height);
                image.rgba = std::move(src.image);
            }
        }
    }

    static GltfWrap wrap(int mode) {
        if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return GltfWrap::ClampToEdge;
        if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return GltfWrap::MirroredRepeat;
        return GltfWrap::Repeat;
    }

    void textures() {
        for (size_t i = 0; i < model_.textures.size(); ++i) {
            const tinygltf::Texture& src = model_.textures[i];
            const std::string what = "texture " + std::to_string(i);
            if (src.source >= 0 && size_t(src.source) >= model_.images.size())
                fail(what + ": image " + std::to_string(src.source) + " does not exist");
            if (src.sampler >= 0 && size_t(src.sampler) >= model_.samplers.size())
                fail(what + ": sampler " + std::to_string(src.sampler) + " does not exist");
            GltfTexture texture;
            texture.image = src.source >= 0 ? uint32_t(src.source) : 0;
            usable_.push_back(src.source >= 0 && !scene_.images[size_t(src.source)].rgba.empty());
            if (src.sampler >= 0) {
                const tinygltf::Sampler& sampler = model_.samplers[size_t(src.sampler)];
                texture.wrapS = wrap(sampler.wrapS);
                texture.wrapT = wrap(sampler.wrapT);
                texture.linearFilter = sampler.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST;
            }
            scene_.textures.push_back(texture);
        }
    }

    // A material's texture reference: checked, and -1 where it cannot be used (with a warning saying why).
    int32_t textureRef(const tinygltf::TextureInfo& info, const std::string& what) {
        return textureRef(info.index, info.texCoord, what);
    }
    int32_t textureRef(int index, int texCoord, const std::string& what) {
        if (index < 0) return -1;
        if (size_t(index) >= model_.textures.size()) fail(what + ": texture " + std::to_string(index) + " does not exist");
        if (texCoord != 0) {
            warn(what + ": reads TEXCOORD_" + std::to_string(texCoord) + ", only TEXCOORD_0 is imported; texture dropped");
            return -1;
        }
        if (options_.decodeImages && !usable_[size_t(index)]) {
            warn(what + ": texture " + std::to_string(index) + " has no decoded image; dropped");
            return -1;
        }
        return index;
    }

    void materials() {
        for (size_t i = 0; i < model_.materials.size(); ++i) {
            const tinygltf::Material& src = model_.materials[i];
            const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
            const std::string what = "material " + std::to_string(i);
            GltfMaterial m;
            m.name = src.name;
            if (pbr.baseColorFactor.size() != 4 || !allFinite(pbr.baseColorFactor))
                fail(what + ": baseColorFactor is not 4 finite numbers");
            if (src.emissiveFactor.size() != 3 || !allFinite(src.emissiveFactor))
                fail(what + ": emissiveFactor is not 3 finite numbers");
            if (!std::isfinite(pbr.metallicFactor) || !std::isfinite(pbr.roughnessFactor) ||
                !std::isfinite(src.alphaCutoff))
                fail(what + ": metallicFactor, roughnessFactor or alphaCutoff is not finite");
            m.baseColorFactor = glm::clamp(glm::vec4(glm::make_vec4(pbr.baseColorFactor.data())), 0.0f, 1.0f);
            m.baseColorTexture = textureRef(pbr.baseColorTexture, what + " baseColorTexture");
            m.metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
            m.roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
            m.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture, what + " metallicRoughnessTexture");
            m.normalTexture = textureRef(src.normalTexture.index, src.normalTexture.texCoord, what + " normalTexture");
            float strength = 1.0f;
            if (auto ext = src.extensions.find("KHR_materials_emissive_strength"); ext != src.extensions.end()) {
                const tinygltf::Value& value = ext->second.Get("emissiveStrength");
                if (value.IsNumber()) strength = float(value.GetNumberAsDouble());
                if (!std::isfinite(strength) || strength < 0.0f) fail(what + ": emissiveStrength is not finite and >= 0");
            }
            m.emissive = glm::max(glm::vec3(glm::make_vec3(src.emissiveFactor.data())), 0.0f) * strength;
            m.emissiveTexture = textureRef(src.emissiveTexture, what + " emissiveTexture");
            if (src.alphaMode == "MASK") m.alphaMode = GltfAlphaMode::Mask;
            else if (src.alphaMode == "BLEND") m.alphaMode = GltfAlphaMode::Blend;
            else if (src.alphaMode != "OPAQUE") fail(what + ": unknown alphaMode '" + src.alphaMode + "'");
            m.alphaCutoff = float(src.alphaCutoff);
            m.doubleSided = src.doubleSided;
            scene_.materials.push_back(m);
        }
    }

    void meshes() {
        std::map<std::array<int, 5>, uint32_t> geometryOf;  // the accessors a geometry was read from
        for (size_t m = 0; m < model_.meshes.size(); ++m) {
            GltfMesh& mesh = scene_.meshes.emplace_back();
            mesh.name = model_.meshes[m].name;
            const auto& primitives = model_.meshes[m].primitives;
            for (size_t p = 0; p < primitives.size(); ++p) {
                const tinygltf::Primitive& src = primitives[p];
                const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
                if (src.mode != TINYGLTF_MODE_TRIANGLES) {
                    warn(what + ": mode " + std::to_string(src.mode) + " is not TRIANGLES; skipped");
                    continue;
                }
                if (src.material < -1 || (src.material >= 0 && size_t(src.material) >= model_.materials.size()))
                    fail(what + ": material " + std::to_string(src.material) + " does not exist");
                const auto attribute = [&](const char* name) {
                    const auto it = src.attributes.find(name);
                    return it == src.attributes.end() ? -1 : it->second;
                };
                const std::array<int, 5> key{attribute("POSITION"), attribute("NORMAL"), attribute("TEXCOORD_0"),
                                             attribute("COLOR_0"), src.indices};
                auto known = geometryOf.find(key);
                if (known == geometryOf.end()) {
                    GltfGeometry geometry = readGeometry(key, what);
                    if (geometry.indices.empty()) {
                        warn(what + ": no triangles; skipped");
                        continue;
                    }
                    known = geometryOf.emplace(key, uint32_t(scene_.geometries.size())).first;
                    scene_.geometries.push_back(std::move(geometry));
                }
                mesh.primitives.push_back({known->second, src.material});
            }
        }
    }

    // accessors: POSITION, NORMAL, TEXCOORD_0, COLOR_0, indices; -1 where absent.
    GltfGeometry readGeometry(const std::array<int, 5>& accessors, const std::string& what) {
        using namespace gltf;
        const AccessorReader reader(model_, name_ + ": " + what + ": ");
        GltfGeometry out;
        const int position = accessors[0];
        if (position < 0) fail(what + ": no POSITION attribute");
        for (const glm::vec4& v : reader.readFloats(position, "POSITION", 3, 3, kFloat)) out.positions.emplace_back(v);
        const size_t vertices = out.positions.size();
        if (const size_t bad = firstNonFinite(out.positions); bad < vertices)
            fail(what + ": accessor " + std::to_string(position) + " (POSITION): vertex " + std::to_string(bad) +
                 " is not finite");

        // Optional attributes must match POSITION's count; a non-finite one is dropped, not fatal.
        const auto optional = [&](int index, const char* name, int minC, int maxC, uint32_t allowed, auto& target) {
            if (index < 0) return;
            std::vector<glm::vec4> values = reader.readFloats(index, name, minC, maxC, allowed);
            if (values.size() != vertices)
                fail(what + ": accessor " + std::to_string(index) + " (" + name + ") has " +
                     std::to_string(values.size()) + " elements but POSITION has " + std::to_string(vertices));
            using Element = typename std::decay_t<decltype(target)>::value_type;
            for (const glm::vec4& v : values) target.push_back(Element(v));
            if (firstNonFinite(target) < vertices) {
                warn(what + ": accessor " + std::to_string(index) + " (" + name + ") has non-finite values; dropped");
                target.clear();
            }
        };
        optional(accessors[1], "NORMAL", 3, 3, kFloat, out.normals);
        optional(accessors[2], "TEXCOORD_0", 2, 2, kFloat | kUByteNorm | kUShortNorm, out.texcoords);
        optional(accessors[3], "COLOR_0", 3, 4, kFloat | kUByteNorm | kUShortNorm, out.colors);

        const int indexAccessor = accessors[4];
        if (indexAccessor < 0) {
            if (vertices % 3)
                fail(what + ": " + std::to_string(vertices) + " vertices without indices is not a multiple of 3");
            for (uint32_t i = 0; i < vertices; i += 3) out.indices.emplace_back(i, i + 1, i + 2);
            return out;
        }
        const std::vector<uint32_t> indices = reader.readIndices(indexAccessor);
        const std::string indexName = "accessor " + std::to_string(indexAccessor) + " (indices)";
        if (indices.size() % 3)
            fail(what + ": " + indexName + ": count " + std::to_string(indices.size()) + " is not a multiple of 3");
        for (size_t i = 0; i < indices.size(); ++i)
            if (indices[i] >= vertices)
                fail(what + ": " + indexName + ": index " + std::to_string(indices[i]) + " out of range for " +
                     std::to_string(vertices) + " vertices (element " + std::to_string(i) + ")");
        out.indices.resize(indices.size() / 3);
        std::memcpy(out.indices.data(), indices.data(), indices.size() * sizeof(uint32_t));
        return out;
    }

    // ---- the node tree

    glm::dmat4 localTransform(const tinygltf::Node& n, size_t index) const {
        const std::string what = "node " + std::to_string(index);
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16 || !allFinite(n.matrix)) fail(what + ": matrix is not 16 finite numbers");
            return glm::make_mat4(n.matrix.data());  // column-major, as glm
        }
        if ((!n.translation.empty() && (n.translation.size() != 3 || !allFinite(n.translation))) ||
            (!n.rotation.empty() && (n.rotation.size() != 4 || !allFinite(n.rotation))) ||
            (!n.scale.empty() && (n.scale.size() != 3 || !allFinite(n.scale))))
            fail(what + ": translation, rotation or scale is malformed or not finite");
        glm::dmat4 m(1.0);
        if (!n.translation.empty()) m = glm::translate(m, glm::make_vec3(n.translation.data()));
        if (!n.rotation.empty()) {  // glTF stores x, y, z, w
            const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
            if (glm::length(q) < 1e-12) fail(what + ": rotation quaternion is zero");
            m *= glm::mat4_cast(glm::normalize(q));
        }
        if (!n.scale.empty()) m = glm::scale(m, glm::make_vec3(n.scale.data()));
        return m;
    }

    void nodes() {
        onPath_.assign(model_.nodes.size(), false);
        visited_.assign(model_.nodes.size(), false);
        if (!model_.scenes.empty()) {
            const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
            if (size_t(sceneIndex) >= model_.scenes.size()) fail("scene " + std::to_string(sceneIndex) + " does not exist");
            for (int root : model_.scenes[size_t(sceneIndex)].nodes) visit(root, glm::dmat4(1.0), 1);
            return;
        }
        // No scene: glTF leaves the choice to the application; take every node that is nobody's child.
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const tinygltf::Node& n : model_.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
        for (size_t i = 0; i < model_.nodes.size(); ++i)
            if (!isChild[i]) visit(int(i), glm::dmat4(1.0), 1);
    }

    void visit(int index, const glm::dmat4& parent, uint32_t depth) {
        if (index < 0 || size_t(index) >= model_.nodes.size())
            fail("node " + std::to_string(index) + " does not exist (the file has " +
                 std::to_string(model_.nodes.size()) + " nodes)");
        const std::string what = "node " + std::to_string(index);
        if (onPath_[size_t(index)]) fail(what + ": cycle in the node hierarchy (the node is its own ancestor)");
        // glTF nodes form a strict tree; a second visit would also let a small file demand exponential work.
        if (visited_[size_t(index)]) fail(what + " is reached twice (it has more than one parent)");
        if (depth > options_.maxNodeDepth)
            fail(what + ": node hierarchy deeper than " + std::to_string(options_.maxNodeDepth) + " levels");
        onPath_[size_t(index)] = visited_[size_t(index)] = true;

        const tinygltf::Node& n = model_.nodes[size_t(index)];
        const glm::dmat4 world = parent * localTransform(n, size_t(index));
        const glm::mat4 worldFloat(world);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(worldFloat[c][r])) fail(what + ": world transform is not finite in single precision");
        if (n.mesh >= 0) {
            if (size_t(n.mesh) >= scene_.meshes.size()) fail(what + ": mesh " + std::to_string(n.mesh) + " does not exist");
            scene_.instances.push_back({uint32_t(n.mesh), uint32_t(index), worldFloat});
        }
        if (n.camera >= 0) camera(n, index, world);
        if (auto ext = n.extensions.find("KHR_lights_punctual"); ext != n.extensions.end())
            light(ext->second.Get("light"), index, world);
        for (int child : n.children) visit(child, world, depth + 1);
        onPath_[size_t(index)] = false;
    }

    void camera(const tinygltf::Node& n, int nodeIndex, const glm::dmat4& world) {
        const std::string what = "node " + std::to_string(nodeIndex) + ": camera " + std::to_string(n.camera);
        if (size_t(n.camera) >= model_.cameras.size()) fail(what + " does not exist");
        const tinygltf::Camera& src = model_.cameras[size_t(n.camera)];
        GltfCamera c;
        c.name = src.name.empty() ? n.name : src.name;
        if (src.type == "perspective") {
            c.kind = GltfCamera::Kind::Perspective;
            c.yfov = float(src.perspective.yfov);
            c.aspectRatio = float(src.perspective.aspectRatio);
            c.znear = float(src.perspective.znear);
            c.zfar = float(src.perspective.zfar);
            if (!(c.yfov > 0.0f && c.yfov < 3.1415926f)) fail(what + ": yfov must lie in (0, pi)");
        } else if (src.type == "orthographic") {
            c.kind = GltfCamera::Kind::Orthographic;
            c.xmag = float(src.orthographic.xmag);
            c.ymag = float(src.orthographic.ymag);
            c.znear = float(src.orthographic.znear);
            c.zfar = float(src.orthographic.zfar);
            if (!(std::isfinite(c.ymag) && c.ymag != 0.0f)) fail(what + ": ymag must be finite and non-zero");
        } else {
            fail(what + ": unknown type '" + src.type + "'");
        }
        c.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
        c.direction = glm::vec3(glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0))));
        c.up = glm::vec3(glm::normalize(glm::dvec3(world * glm::dvec4(0, 1, 0, 0))));
        if (firstNonFinite(std::vector<glm::vec3>{c.position, c.direction, c.up}) < 3)
            fail(what + ": the node transform leaves no valid view (singular?)");
        scene_.cameras.push_back(c);
    }

    void light(const tinygltf::Value& lightIndex, int nodeIndex, const glm::dmat4& world) {
        const std::string what = "node " + std::to_string(nodeIndex) + ": KHR_lights_punctual light";
        if (!lightIndex.IsNumber()) fail(what + " index is missing or not a number");
        const int index = lightIndex.GetNumberAsInt();
        if (index < 0 || size_t(index) >= model_.lights.size())
            fail(what + " " + std::to_string(index) + " does not exist");
        const tinygltf::Light& src = model_.lights[size_t(index)];
        GltfLight l;
        l.name = src.name;
        if (src.type == "directional") l.kind = GltfLight::Kind::Directional;
        else if (src.type == "point") l.kind = GltfLight::Kind::Point;
        else if (src.type == "spot") l.kind = GltfLight::Kind::Spot;
        else fail(what + " " + std::to_string(index) + ": unknown type '" + src.type + "'");
        if (!src.color.empty()) {
            if (src.color.size() != 3 || !allFinite(src.color)) fail(what + ": color is not 3 finite numbers");
            l.color = glm::vec3(glm::make_vec3(src.color.data()));
        }
        l.intensity = float(src.intensity);
        l.range = float(src.range);
        l.innerConeAngle = float(src.spot.innerConeAngle);
        l.outerConeAngle = float(src.spot.outerConeAngle);
        if (!std::isfinite(l.intensity) || l.intensity < 0.0f) fail(what + ": intensity is not finite and >= 0");
        if (l.kind == GltfLight::Kind::Spot &&
            !(l.innerConeAngle >= 0.0f && l.innerConeAngle < l.outerConeAngle && l.outerConeAngle <= 1.5707964f))
            fail(what + ": spot cone angles must satisfy 0 <= inner < outer <= pi/2");
        l.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
        l.direction = glm::vec3(glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0))));
        if (firstNonFinite(std::vector<glm::vec3>{l.position, l.direction}) < 2)
            fail(what + ": the node transform leaves no valid direction (singular?)");
        scene_.lights.push_back(l);
    }

    void bounds() {
        std::vector<glm::vec3> lo(scene_.meshes.size(), glm::vec3(INFINITY)), hi(scene_.meshes.size(), glm::vec3(-INFINITY));
        for (size_t m = 0; m < scene_.meshes.size(); ++m)
            for (const GltfPrimitive& p : scene_.meshes[m].primitives)
                for (const glm::vec3& v : scene_.geometries[p.geometry].positions) {
                    lo[m] = glm::min(lo[m], v);
                    hi[m] = glm::max(hi[m], v);
                }
        glm::vec3 worldLo(INFINITY), worldHi(-INFINITY);
        for (const GltfMeshInstance& instance : scene_.instances) {
            if (lo[instance.mesh].x > hi[instance.mesh].x) continue;  // a mesh whose primitives were all skipped
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? hi[instance.mesh].x : lo[instance.mesh].x,
                                  (corner & 2) ? hi[instance.mesh].y : lo[instance.mesh].y,
                                  (corner & 4) ? hi[instance.mesh].z : lo[instance.mesh].z);
                const glm::vec3 w = glm::vec3(instance.transform * glm::vec4(p, 1.0f));
                worldLo = glm::min(worldLo, w);
                worldHi = glm::max(worldHi, w);
            }
        }
        if (worldLo.x <= worldHi.x) {
            scene_.boundsMin = worldLo;
            scene_.boundsMax = worldHi;
        }
    }

    tinygltf::Model& model_;
    const GltfLoadOptions& options_;
    GltfScene& scene_;
    std::string name_;
    std::vector<bool> usable_;   // per texture: its image was decoded
    std::vector<bool> onPath_;   // per node: an ancestor of the node being visited
    std::vector<bool> visited_;
};

}  // namespace

GltfScene loadGltf(const std::filesystem::path& file, const GltfLoadOptions& options) {
    GltfScene scene;
    scene.file = file;
    tinygltf::Model model;
    gltf::parseFile(file, options, model, scene.warnings);
    Converter(model, options, scene).run();
    return scene;
}

}  // namespace ripple::apps
