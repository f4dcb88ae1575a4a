// GltfScene -> ANARI objects. Objects are made once and shared as the glTF file shares them: a geometry per
// distinct vertex data, a surface per geometry and material, a group per mesh, an instance per node.
#include "apps/scene/AnariScene.h"

#include "apps/scene/AnariParams.h"
#include "apps/scene/SceneEdits.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace ripple::apps {

using anari::set;
using anari::setObject;

namespace {

const char* wrapName(GltfWrap wrap) {
    switch (wrap) {
        case GltfWrap::ClampToEdge: return "clampToEdge";
        case GltfWrap::MirroredRepeat: return "mirrorRepeat";
        default: return "repeat";
    }
}

class WorldBuilder {
public:
    WorldBuilder(ANARIDevice d, const GltfScene& scene, bool withLights, const std::vector<ANARILight>& extraLights,
                 SceneEdits* edits)
        : d_(d), scene_(scene), withLights_(withLights), extraLights_(extraLights), edits_(edits), handles_(d) {}

    AnariWorld build() {
        std::vector<ANARIGroup> groups(scene_.meshes.size(), nullptr);
        for (size_t m = 0; m < scene_.meshes.size(); ++m) groups[m] = group(scene_.meshes[m]);

        std::vector<ANARIInstance> instances;
        for (const GltfMeshInstance& gi : scene_.instances) {
            if (!groups[gi.mesh]) continue;  // a mesh whose primitives were all skipped
            ANARIInstance instance = handles_.keep(anariNewInstance(d_, "transform"), "instance");
            set(d_, instance, "transform", gi.transform);
            setObject(d_, instance, "group", ANARI_GROUP, groups[gi.mesh]);
            anariCommitParameters(d_, instance);
            instances.push_back(instance);
        }
        std::vector<ANARILight> lights = extraLights_;
        for (size_t i = 0; i < scene_.lights.size(); ++i) {
            const GltfLight& l = scene_.lights[i];
            lights.push_back(light(l, l.name.empty() ? "light " + std::to_string(i) : l.name));
        }

        AnariWorld out;
        out.background = glm::vec4(0.08f, 0.08f, 0.09f, 1.0f);
        // Uniformly emissive materials light a scene (a lamp's panel); emission through a texture is
        // detail (glowing decals) that leaves the rest dark.
        const bool emits = std::any_of(scene_.materials.begin(), scene_.materials.end(), [](const GltfMaterial& m) {
            return m.emissive != glm::vec3(0.0f) && m.emissiveTexture < 0;
        });
        if (lights.empty() && !emits) {
            // Many glTF files (scanned or sample models) carry no light: a key light from the upper front
            // left and a grey ambient fill, as a studio would, instead of a black image. The key is a disc
            // the size of the sun seen from the earth (0.53 degrees): unlike a delta light, its highlight on
            // a mirror-like metal is found by BSDF sampling, not only by a rare light sample.
            GltfLight key;
            key.kind = GltfLight::Kind::Directional;
            key.direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.6f));
            key.intensity = 2.0f;
            key.angularDiameter = kStudioSunAngularDiameter;
            lights.push_back(light(key, "studio key light"));
            out.ambientRadiance = 0.4f;
            out.background = glm::vec4(0.35f, 0.35f, 0.38f, 1.0f);
        }
        out.world = anariNewWorld(d_);
        if (!out.world) throw std::runtime_error("the ANARI device returned no world");
        if (!instances.empty()) {
            ANARIArray1D array = handles_.keep(anari::newArray1D(d_, instances, ANARI_INSTANCE), "array");
            setObject(d_, out.world, "instance", ANARI_ARRAY1D, array);
        }
        if (!lights.empty() && withLights_) {
            ANARIArray1D array = handles_.keep(anari::newArray1D(d_, lights, ANARI_LIGHT), "array");
            setObject(d_, out.world, "light", ANARI_ARRAY1D, array);
        }
        anariCommitParameters(d_, out.world);
        for (const GltfCamera& c : scene_.cameras) out.cameras.push_back(cameraView(c));
        out.boundsMin = scene_.boundsMin;
        out.boundsMax = scene_.boundsMax;
        return out;
    }

private:
    ANARIGroup group(const GltfMesh& mesh) {
        std::vector<ANARISurface> surfaces;
        for (const GltfPrimitive& p : mesh.primitives) surfaces.push_back(surface(p));
        if (surfaces.empty()) return nullptr;
        ANARIGroup g = handles_.keep(anariNewGroup(d_), "group");
        ANARIArray1D array = handles_.keep(anari::newArray1D(d_, surfaces, ANARI_SURFACE), "array");
        setObject(d_, g, "surface", ANARI_ARRAY1D, array);
        anariCommitParameters(d_, g);
        return g;
    }

    ANARISurface surface(const GltfPrimitive& p) {
        const GltfGeometry& g = scene_.geometries[p.geometry];
        // Vertex colors replace the base color only where no texture supplies it.
        const bool useColors = !g.colors.empty() && !(p.material >= 0 && baseTexture(p.material) >= 0);
        const std::tuple<uint32_t, int32_t, bool> key{p.geometry, p.material, useColors};
        if (auto it = surfaces_.find(key); it != surfaces_.end()) return it->second;
        ANARISurface s = handles_.keep(anariNewSurface(d_), "surface");
        setObject(d_, s, "geometry", ANARI_GEOMETRY, geometry(p.geometry));
        setObject(d_, s, "material", ANARI_MATERIAL, material(p.material, useColors));
        anariCommitParameters(d_, s);
        return surfaces_[key] = s;
    }

    int32_t baseTexture(int32_t material) const { return usable(scene_.materials[size_t(material)].baseColorTexture); }

    // The texture index where its image holds pixels, else -1 (a scene read without decoding images).
    int32_t usable(int32_t texture) const {
        if (texture < 0) return -1;
        return scene_.images[scene_.textures[size_t(texture)].image].rgba.empty() ? -1 : texture;
    }

    ANARIGeometry geometry(uint32_t index) {
        if (auto it = geometries_.find(index); it != geometries_.end()) return it->second;
        const GltfGeometry& g = scene_.geometries[index];
        ANARIGeometry geom = handles_.keep(anariNewGeometry(d_, "triangle"), "triangle geometry");
        const auto attach = [&](const char* name, auto& values) {
            if (values.empty()) return;
            ANARIArray1D array = handles_.keep(anari::newArray1D(d_, values), "array");
            setObject(d_, geom, name, ANARI_ARRAY1D, array);
        };
        attach("vertex.position", g.positions);
        attach("primitive.index", g.indices);
        attach("vertex.normal", g.normals);
        attach("vertex.attribute0", g.texcoords);  // ANARI 1.0 triangles have no texcoord; samplers read this
        attach("vertex.color", g.colors);
        anariCommitParameters(d_, geom);
        return geometries_[index] = geom;
    }

    // An image as a 2D array, sRGB-encoded (colours) or linear (data such as metallic-roughness).
    ANARIArray2D imageArray(uint32_t image, bool srgb) {
        const std::pair<uint32_t, bool> key{image, srgb};
        if (auto it = images_.find(key); it != images_.end()) return it->second;
        const GltfImage& src = scene_.images[image];
        ANARIArray2D array = handles_.keep(
            anariNewArray2D(d_, nullptr, nullptr, nullptr, srgb ? ANARI_UFIXED8_RGBA_SRGB : ANARI_UFIXED8_VEC4,
                            src.width, src.height),
            "2D array");
        void* mapped = anariMapArray(d_, array);
        if (!mapped) throw std::runtime_error("the ANARI device could not map an image array");
        std::memcpy(mapped, src.rgba.data(), src.rgba.size());
        anariUnmapArray(d_, array);
        return images_[key] = array;
    }

    // An image2D sampler over texture `texture`, whose texels are multiplied by `outTransform` (ANARI's
    // way to apply glTF factors and to move a channel into the first component a float parameter reads).
    ANARISampler sampler(int32_t texture, bool srgb, const glm::mat4& outTransform) {
        const GltfTexture& t = scene_.textures[size_t(texture)];
        ANARISampler s = handles_.keep(anariNewSampler(d_, "image2D"), "image2D sampler");
        setObject(d_, s, "image", ANARI_ARRAY2D, imageArray(t.image, srgb));
        set(d_, s, "inAttribute", "attribute0");
        set(d_, s, "filter", t.linearFilter ? "linear" : "nearest");
        set(d_, s, "wrapMode1", wrapName(t.wrapS));
        set(d_, s, "wrapMode2", wrapName(t.wrapT));
        set(d_, s, "outTransform", outTransform);
        anariCommitParameters(d_, s);
        return s;
    }

    // A matrix whose first row picks channel `channel` of a texel, times `scale`.
    static glm::mat4 pickChannel(int channel, float scale) {
        glm::mat4 m(0.0f);
        m[channel][0] = scale;  // glm indexes [column][row]
        return m;
    }

    ANARIMaterial material(int32_t index, bool useColors) {
        const std::pair<int32_t, bool> key{index, useColors};
        if (auto it = materials_.find(key); it != materials_.end()) return it->second;
        GltfMaterial m = index >= 0 ? scene_.materials[size_t(index)] : GltfMaterial{};
        m.baseColorTexture = usable(m.baseColorTexture);
        m.metallicRoughnessTexture = usable(m.metallicRoughnessTexture);
        m.emissiveTexture = usable(m.emissiveTexture);
        m.normalTexture = usable(m.normalTexture);
        ANARIMaterial mat = handles_.keep(anariNewMaterial(d_, "physicallyBased"), "physicallyBased material");
        const glm::vec4 factor = m.baseColorFactor;
        if (m.baseColorTexture >= 0) {
            ANARISampler s = sampler(m.baseColorTexture, true, glm::mat4(glm::vec4(factor.r, 0, 0, 0), glm::vec4(0, factor.g, 0, 0),
                                                                         glm::vec4(0, 0, factor.b, 0), glm::vec4(0, 0, 0, factor.a)));
            setObject(d_, mat, "baseColor", ANARI_SAMPLER, s);
        } else if (useColors) {
            set(d_, mat, "baseColor", "color");  // the geometry's vertex.color
        } else {
            set(d_, mat, "baseColor", glm::vec3(factor));
        }
        if (m.alphaMode != GltfAlphaMode::Opaque && m.baseColorTexture >= 0)
            setObject(d_, mat, "opacity", ANARI_SAMPLER, sampler(m.baseColorTexture, true, pickChannel(3, factor.a)));
        else
            set(d_, mat, "opacity", factor.a);
        if (m.metallicRoughnessTexture >= 0) {
            // glTF keeps roughness in G and metallic in B.
            setObject(d_, mat, "metallic", ANARI_SAMPLER, sampler(m.metallicRoughnessTexture, false, pickChannel(2, m.metallic)));
            setObject(d_, mat, "roughness", ANARI_SAMPLER, sampler(m.metallicRoughnessTexture, false, pickChannel(1, m.roughness)));
        } else {
            set(d_, mat, "metallic", m.metallic);
            set(d_, mat, "roughness", m.roughness);
        }
        if (m.emissiveTexture >= 0 && m.emissive != glm::vec3(0.0f)) {
            const glm::vec3 e = m.emissive;
            ANARISampler s = sampler(m.emissiveTexture, true, glm::mat4(glm::vec4(e.r, 0, 0, 0), glm::vec4(0, e.g, 0, 0),
                                                                        glm::vec4(0, 0, e.b, 0), glm::vec4(0, 0, 0, 1)));
            setObject(d_, mat, "emissive", ANARI_SAMPLER, s);
        } else if (m.emissive != glm::vec3(0.0f)) {
            set(d_, mat, "emissive", m.emissive);
        }
        if (m.normalTexture >= 0)  // tangent-space, linear rgb in [0, 1] as glTF stores it
            setObject(d_, mat, "normal", ANARI_SAMPLER, sampler(m.normalTexture, false, glm::mat4(1.0f)));
        set(d_, mat, "alphaMode", m.alphaMode == GltfAlphaMode::Mask    ? "mask"
                                  : m.alphaMode == GltfAlphaMode::Blend ? "blend"
                                                                        : "opaque");
        set(d_, mat, "alphaCutoff", m.alphaCutoff);
        anariCommitParameters(d_, mat);
        return materials_[key] = mat;
    }

    // `label` names it in a viewer's light panel (edits_).
    ANARILight light(const GltfLight& l, const std::string& label) {
        static const char* kinds[] = {"directional", "point", "spot"};
        ANARILight light = handles_.keep(anariNewLight(d_, kinds[int(l.kind)]), "light");
        set(d_, light, "color", l.color);
        if (l.kind == GltfLight::Kind::Directional) {
            set(d_, light, "direction", l.direction);
            set(d_, light, "irradiance", l.intensity);
            if (l.angularDiameter > 0.0f) set(d_, light, "angularDiameter", l.angularDiameter);
        } else {
            set(d_, light, "position", l.position);
            set(d_, light, "intensity", l.intensity);
        }
        if (l.kind == GltfLight::Kind::Spot) {
            // glTF gives half angles from the axis; ANARI the full opening and the width of the falloff ring.
            set(d_, light, "direction", l.direction);
            set(d_, light, "openingAngle", 2.0f * l.outerConeAngle);
            set(d_, light, "falloffAngle", l.outerConeAngle - l.innerConeAngle);
        }
        anariCommitParameters(d_, light);
        if (edits_ && withLights_) {
            const bool aimed = l.kind != GltfLight::Kind::Point;
            edits_->add({light, label, kinds[int(l.kind)], l.color, l.intensity,
                         aimed ? std::optional<glm::vec3>(l.direction) : std::nullopt, 0.0f});
        }
        return light;
    }

    ANARIDevice d_;
    const GltfScene& scene_;
    bool withLights_ = true;
    std::vector<ANARILight> extraLights_;
    SceneEdits* edits_ = nullptr;
    anari::HandleList handles_;
    std::map<uint32_t, ANARIGeometry> geometries_;
    std::map<std::pair<uint32_t, bool>, ANARIArray2D> images_;
    std::map<std::pair<int32_t, bool>, ANARIMaterial> materials_;
    std::map<std::tuple<uint32_t, int32_t, bool>, ANARISurface> surfaces_;
};

}  // namespace

AnariWorld buildAnariWorld(ANARIDevice device, const GltfScene& scene, bool withLights,
                           const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    return WorldBuilder(device, scene, withLights, extraLights, edits).build();
}

CameraView cameraView(const GltfCamera& camera) {
    CameraView view;
    view.name = camera.name;
    view.orthographic = camera.kind == GltfCamera::Kind::Orthographic;
    view.position = camera.position;
    view.direction = camera.direction;
    view.up = camera.up;
    view.fovy = camera.yfov;
    view.height = 2.0f * std::abs(camera.ymag);
    return view;
}

CameraView frameBounds(const glm::vec3& lo, const glm::vec3& hi, float aspect) {
    CameraView view;
    view.name = "framed";
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return view;  // empty scene: the default view
    const glm::vec3 center = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
    // The narrower of the two fields of view decides the distance that fits the bounding sphere.
    const float halfY = 0.5f * view.fovy;
    const float halfX = std::atan(std::tan(halfY) * std::max(aspect, 1e-3f));
    const float distance = 1.05f * radius / std::sin(std::min(halfX, halfY));
    const glm::vec3 from = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));
    view.position = center + distance * from;
    view.direction = -from;
    view.up = glm::vec3(0.0f, 1.0f, 0.0f);
    view.height = 2.1f * radius;
    return view;
}

void setAnariCamera(ANARIDevice device, ANARICamera camera, const CameraView& view, float aspect) {
    set(device, camera, "position", view.position);
    set(device, camera, "direction", view.direction);
    set(device, camera, "up", view.up);
    set(device, camera, "aspect", aspect);
    if (view.orthographic) {
        set(device, camera, "height", view.height);
    } else {
        set(device, camera, "fovy", view.fovy);
        // Only a lens is set, so that a device without depth of field is not told of a pinhole.
        if (view.apertureRadius > 0.0f) {
            set(device, camera, "apertureRadius", view.apertureRadius);
            set(device, camera, "focusDistance", view.focusDistance);
        } else {
            anariUnsetParameter(device, camera, "apertureRadius");
            anariUnsetParameter(device, camera, "focusDistance");
        }
    }
    anariCommitParameters(device, camera);
}

ANARICamera newAnariCamera(ANARIDevice device, const CameraView& view, float aspect) {
    ANARICamera camera = anariNewCamera(device, view.orthographic ? "orthographic" : "perspective");
    if (!camera) throw std::runtime_error("the ANARI device returned no camera");
    setAnariCamera(device, camera, view, aspect);
    return camera;
}

}  // namespace ripple::apps
