// The walk over a committed world that SceneSync and the world's bounds share, and the description built
// from it (see SceneSync.h).
#include "anari/device/scene/SceneSync.h"

#include "anari/device/world/World.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace ripple::device {
namespace {

// The id of an object whose "id" is unset, and the instance id of surfaces and lights placed directly in
// the world, which no instance names (KHR_FRAME_CHANNEL_OBJECT_ID / _INSTANCE_ID: 4294967295).
constexpr uint32_t kNoInstance = std::numeric_limits<uint32_t>::max();

struct Placement {
    glm::mat4 transform{1.0f};
    uint32_t instanceId = kNoInstance;
    const Instance* instance = nullptr;  // none for surfaces placed directly in the world
};

// Calls onSurface(surface, placement, objectId) for every renderable surface, onVolume(volume, placement,
// objectId) for every renderable volume and onLight(light, placement) for every valid light, in the order the
// application gave them. Unset ids are ~0u, as the spec says.
template <class OnSurface, class OnVolume, class OnLight>
void forEachPlaced(const World& world, OnSurface&& onSurface, OnVolume&& onVolume, OnLight&& onLight) {
    auto placeGroup = [&](const std::vector<Surface*>& surfaces, const std::vector<Volume*>& volumes,
                          const std::vector<Light*>& lights, const Placement& placement) {
        for (size_t i = 0; i < surfaces.size(); ++i)
            if (surfaces[i]->renderable()) onSurface(*surfaces[i], placement, surfaces[i]->id().value_or(kNoInstance));
        for (Volume* volume : volumes)
            if (volume->renderable()) onVolume(*volume, placement, volume->id().value_or(kNoInstance));
        for (Light* light : lights)
            if (light->isValid()) onLight(*light, placement);
    };
    placeGroup(world.surfaces(), world.volumes(), world.lights(), Placement{});
    for (size_t i = 0; i < world.instances().size(); ++i) {
        const Instance& instance = *world.instances()[i];
        if (!instance.isValid() || !instance.group() || !instance.group()->isValid()) continue;
        placeGroup(instance.group()->surfaces(), instance.group()->volumes(), instance.group()->lights(),
                   Placement{instance.transform(), instance.id().value_or(kNoInstance), &instance});
    }
}

// Lights reach core in world space.
core::Light placedLight(core::Light light, const glm::mat4& transform) {
    const glm::mat3 linear(transform);
    light.position = glm::vec3(transform * glm::vec4(light.position, 1.0f));
    light.direction = glm::normalize(linear * light.direction);
    light.edge1 = linear * light.edge1;
    light.edge2 = linear * light.edge2;
    light.up = linear * light.up;
    return light;
}

core::GeometryIdentity identityOf(const Geometry& geometry) {
    return core::GeometryIdentity{reinterpret_cast<uintptr_t>(&geometry), geometry.lastCommitted()};
}

// Builds a description from a committed world, sharing one core geometry, material and texture between
// all the placements that use the same ANARI object.
class DescriptionBuilder {
public:
    core::SceneDescription build(const World& world) {
        forEachPlaced(
            world,
            [&](const Surface& surface, const Placement& placement, uint32_t objectId) {
                core::InstanceDescription instance;
                instance.geometry = geometryRef(*surface.geometry());
                instance.transform = placement.transform;
                instance.materialIndex = materialIndex(*surface.material());
                instance.objectId = objectId;
                instance.instanceId = placement.instanceId;
                if (placement.instance) {
                    instance.color = placement.instance->color();
                    instance.attributes = placement.instance->attributes();
                }
                description_.instances.push_back(instance);
            },
            [&](const Volume& volume, const Placement& placement, uint32_t objectId) {
                description_.volumes.push_back(volume.volume());
                description_.volumes.back().transform = placement.transform;
                description_.volumes.back().objectId = objectId;
                description_.volumes.back().instanceId = placement.instanceId;
            },
            [&](const Light& light, const Placement& placement) {
                description_.lights.push_back(placedLight(light.light(), placement.transform));
                if (const core::Texture* image = light.image()) description_.lights.back().texture = lightImageIndex(light, *image);
            });
        return std::move(description_);
    }

private:
    core::GeometryRef geometryRef(const Geometry& geometry) {
        auto [it, added] = geometries_.try_emplace(&geometry);
        if (!added) return it->second;
        core::GeometryRef& ref = it->second;
        if (const auto* mesh = std::get_if<core::TriangleMesh>(&geometry.shape())) {
            ref = {core::GeometryKind::Triangles, uint32_t(description_.meshes.size())};
            description_.meshes.push_back(*mesh);
            description_.meshes.back().identity = identityOf(geometry);
        } else if (const auto* spheres = std::get_if<core::SphereSet>(&geometry.shape())) {
            ref = {core::GeometryKind::Spheres, uint32_t(description_.sphereSets.size())};
            description_.sphereSets.push_back(*spheres);
            description_.sphereSets.back().identity = identityOf(geometry);
        } else if (const auto* cylinders = std::get_if<core::CylinderSet>(&geometry.shape())) {
            ref = {core::GeometryKind::Cylinders, uint32_t(description_.cylinderSets.size())};
            description_.cylinderSets.push_back(*cylinders);
            description_.cylinderSets.back().identity = identityOf(geometry);
        } else if (const auto* cones = std::get_if<core::ConeSet>(&geometry.shape())) {
            ref = {core::GeometryKind::Cones, uint32_t(description_.coneSets.size())};
            description_.coneSets.push_back(*cones);
            description_.coneSets.back().identity = identityOf(geometry);
        } else if (const auto* isosurfaces = std::get_if<core::IsosurfaceSet>(&geometry.shape())) {
            ref = {core::GeometryKind::Isosurfaces, uint32_t(description_.isosurfaceSets.size())};
            description_.isosurfaceSets.push_back(*isosurfaces);
            description_.isosurfaceSets.back().identity = identityOf(geometry);
        }
        return ref;
    }

    uint32_t materialIndex(const Material& material) {
        auto [it, added] = materials_.try_emplace(&material, uint32_t(description_.materials.size()));
        if (!added) return it->second;
        core::Material described = material.material();
        for (size_t slot = 0; slot < kTextureSlotCount; ++slot) {
            if (const Sampler* sampler = material.sampler(TextureSlot(slot)); sampler && sampler->isValid() && sampler->texture())
                textureIndexOf(described, TextureSlot(slot)) = textureIndex(*sampler);
            else if (const auto input = material.attribute(TextureSlot(slot)))
                textureIndexOf(described, TextureSlot(slot)) = attributeTextureIndex(*input);
        }
        description_.materials.push_back(described);
        return it->second;
    }

    int32_t lightImageIndex(const Light& light, const core::Texture& image) {
        auto [it, added] = lightImages_.try_emplace(&light, int32_t(description_.textures.size()));
        if (added) description_.textures.push_back(image);
        return it->second;
    }

    int32_t textureIndex(const Sampler& sampler) {
        auto [it, added] = textures_.try_emplace(&sampler, int32_t(description_.textures.size()));
        if (added) description_.textures.push_back(*sampler.texture());
        return it->second;
    }

    // A material parameter given as an attribute name: the identity transform texture of that input.
    int32_t attributeTextureIndex(core::Texture::Input input) {
        auto [it, added] = attributeTextures_.try_emplace(input, int32_t(description_.textures.size()));
        if (added) description_.textures.push_back(core::Texture{.kind = core::Texture::Kind::Transform, .input = input});
        return it->second;
    }

    core::SceneDescription description_;
    std::unordered_map<const Geometry*, core::GeometryRef> geometries_;
    std::unordered_map<const Material*, uint32_t> materials_;
    std::unordered_map<const Sampler*, int32_t> textures_;
    std::unordered_map<core::Texture::Input, int32_t> attributeTextures_;
    std::unordered_map<const Light*, int32_t> lightImages_;
};

}  // namespace

SceneSync::SceneSync() = default;
SceneSync::~SceneSync() = default;

bool SceneSync::update(World& world) {
    const uint64_t newest = world.refreshSubtree(SceneObject::newWalk());
    if (&world == world_ && newest == newestStamp_ && scene_) return false;
    world_ = &world;
    newestStamp_ = newest;
    // The other ranks' emitters stay until the next exchange says otherwise (usually they did not change).
    std::vector<gpu::LightRecord> foreign = std::move(description_.foreignTriangleLights);
    description_ = DescriptionBuilder().build(world);
    description_.foreignTriangleLights = std::move(foreign);
    localLights_ = description_.lights;
    pending_ = true;
    return true;
}

bool SceneSync::lit() const {
    if (!description_.lights.empty()) return true;
    return std::any_of(description_.materials.begin(), description_.materials.end(), [](const core::Material& m) {
        return glm::any(glm::greaterThan(m.emissive, glm::vec3(0.0f))) || m.emissiveTexture != core::kNoTexture;
    });
}

bool SceneSync::setLights(const std::vector<core::Light>& lights, float worldRadius, float worldMagnitude) {
    // Byte comparison: lights are plain data, and a rank whose lights did not change sends the same bytes.
    const bool same = lights.size() == description_.lights.size() &&
                      (lights.empty() || std::memcmp(static_cast<const void*>(lights.data()), description_.lights.data(),
                                                     lights.size() * sizeof(core::Light)) == 0);
    if (same && description_.lightSceneRadius == worldRadius && description_.worldMagnitude == worldMagnitude)
        return false;
    description_.lights = lights;
    description_.lightSceneRadius = worldRadius;
    description_.worldMagnitude = worldMagnitude;
    pending_ = true;
    return true;
}

bool SceneSync::setForeignTriangleLights(std::vector<gpu::LightRecord> lights) {
    std::vector<gpu::LightRecord>& current = description_.foreignTriangleLights;
    if (lights.size() == current.size() &&
        (lights.empty() || std::memcmp(lights.data(), current.data(), lights.size() * sizeof(gpu::LightRecord)) == 0))
        return false;
    current = std::move(lights);
    pending_ = true;
    return true;
}

void SceneSync::setTraversal(core::Traversal traversal) {
    if (traversal == traversal_) return;
    traversal_ = traversal;
    pending_ = true;
}

const core::Scene& SceneSync::scene(const vk::Context& context, bool& rebuilt) {
    rebuilt = pending_ || !scene_;
    if (rebuilt) {
        scene_ = std::make_unique<core::Scene>(context, description_, bvh::BuildOptions{}, scene_.get(), traversal_);
        pending_ = false;
        ++builds_;
    }
    return *scene_;
}

bvh::Aabb worldBounds(World& world) {
    world.refreshSubtree(SceneObject::newWalk());
    bvh::Aabb bounds;
    forEachPlaced(
        world,
        [&](const Surface& surface, const Placement& placement, uint32_t) {
            const bvh::Aabb& local = surface.geometry()->bounds();
            if (local.empty()) return;
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? local.hi.x : local.lo.x, (corner & 2) ? local.hi.y : local.lo.y,
                                  (corner & 4) ? local.hi.z : local.lo.z);
                bounds.extend(glm::vec3(placement.transform * glm::vec4(p, 1.0f)));
            }
        },
        [&](const Volume& volume, const Placement& placement, uint32_t) {
            const bvh::Aabb local = volume.bounds();
            if (local.empty()) return;
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? local.hi.x : local.lo.x, (corner & 2) ? local.hi.y : local.lo.y,
                                  (corner & 4) ? local.hi.z : local.lo.z);
                bounds.extend(glm::vec3(placement.transform * glm::vec4(p, 1.0f)));
            }
        },
        [](const Light&, const Placement&) {});
    return bounds;
}

}  // namespace ripple::device
