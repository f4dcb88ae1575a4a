"""Small scenes for the pynari tests: a triangle pair over a floor and spheres, 64x64 pixels, few samples."""
import numpy as np
import pynari as anari

SIZE = (64, 64)


def camera(device):
    cam = device.newCamera('perspective')
    cam.setParameter('aspect', anari.FLOAT32, SIZE[0] / SIZE[1])
    cam.setParameter('position', anari.float3, (0.0, 0.5, -3.0))
    cam.setParameter('direction', anari.float3, (0.0, -0.1, 1.0))
    cam.setParameter('up', anari.float3, (0.0, 1.0, 0.0))
    cam.commitParameters()
    return cam


def triangles(device):
    """A quad as two triangles, as pynari's samples pass them: flat float32 and uint32 arrays."""
    mesh = device.newGeometry('triangle')
    mesh.setParameter('vertex.position', anari.ARRAY1D, device.newArray1D(anari.FLOAT32_VEC3, np.array(
        [-1, -1, 0.5, 1, -1, 0.5, -1, 1, 0.5, 1, 1, 0.5], dtype=np.float32)))
    mesh.setParameter('primitive.index', anari.ARRAY1D,
                      device.newArray1D(anari.UINT32_VEC3, np.array([0, 1, 2, 1, 3, 2], dtype=np.uint32)))
    mesh.commitParameters()
    return mesh


def spheres(device, centers):
    geom = device.newGeometry('sphere')
    geom.setParameter('vertex.position', anari.ARRAY1D,
                      device.newArray1D(anari.float3, np.asarray(centers, dtype=np.float32).reshape(-1, 3)))
    geom.setParameter('radius', anari.FLOAT32, 0.3)
    geom.commitParameters()
    return geom


def surface(device, geometry, color=(0.8, 0.5, 0.3)):
    material = device.newMaterial('matte')
    material.setParameter('color', anari.float3, color)
    material.commitParameters()
    surf = device.newSurface()
    surf.setParameter('geometry', anari.GEOMETRY, geometry)
    surf.setParameter('material', anari.MATERIAL, material)
    surf.commitParameters()
    return surf


def world(device, surfaces, light=True):
    """light: False on all but one rank of a data-parallel world (every rank's lights light all of it)."""
    w = device.newWorld()
    if surfaces:
        w.setParameterArray1D('surface', anari.SURFACE, surfaces)
    if not light:
        w.commitParameters()
        return w
    light = device.newLight('directional')
    light.setParameter('direction', anari.float3, (0.3, -1.0, 0.6))
    light.setParameter('irradiance', anari.float, 2.0)
    light.commitParameters()
    w.setParameterArray1D('light', anari.LIGHT, [light])
    w.commitParameters()
    return w


def frame(device, w, channels=None, samples=2):
    renderer = device.newRenderer('default')
    renderer.setParameter('pixelSamples', anari.INT32, samples)
    renderer.setParameter('background', anari.float4, (0.1, 0.1, 0.2, 1.0))
    renderer.commitParameters()
    f = device.newFrame()
    f.setParameter('size', anari.uint2, SIZE)
    for name, type_ in (channels or {}).items():
        f.setParameter(name, anari.DATA_TYPE, type_)
    f.setParameter('renderer', anari.RENDERER, renderer)
    f.setParameter('camera', anari.CAMERA, camera(device))
    f.setParameter('world', anari.WORLD, w)
    f.commitParameters()
    return f


def not_blank(image):
    rgb = np.asarray(image)[..., :3].astype(np.float64)
    return rgb.std() > 1.0 and rgb.max() > 10
