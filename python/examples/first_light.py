"""pynari's first light on Ripple: two triangles, a light, 256x192 pixels, saved as a PNG.
Usage: PYTHONPATH=build/python python3 python/examples/first_light.py [out.png]"""
import struct
import sys
import zlib

import numpy as np
import pynari as anari


def write_png(path, rgba):
    """An 8-bit RGBA PNG from an (h, w, 4) uint8 array, top row first."""
    h, w, _ = rgba.shape
    rows = b''.join(b'\x00' + rgba[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(rows)) + chunk(b'IEND', b''))


width, height = 256, 192
device = anari.newDevice('default')  # Ripple, or the library named by ANARI_LIBRARY

camera = device.newCamera('perspective')
camera.setParameter('aspect', anari.FLOAT32, width / height)
camera.setParameter('position', anari.float3, (0.0, 0.0, 0.0))
camera.setParameter('direction', anari.float3, (0.1, 0.0, 1.0))
camera.setParameter('up', anari.float3, (0.0, 1.0, 0.0))
camera.commitParameters()

mesh = device.newGeometry('triangle')
mesh.setParameterArray1D('vertex.position', anari.FLOAT32_VEC3, np.array(
    [[-1, -1, 3], [-1, 1, 3], [1, -1, 3], [0.1, 0.1, 0.3]], dtype=np.float32))
mesh.setParameterArray1D('vertex.color', anari.FLOAT32_VEC4, np.array(
    [[0.9, 0.5, 0.5, 1], [0.8, 0.8, 0.8, 1], [0.8, 0.8, 0.8, 1], [0.5, 0.9, 0.5, 1]], dtype=np.float32))
mesh.setParameterArray1D('primitive.index', anari.UINT32_VEC3, np.array([[0, 1, 2], [1, 2, 3]], dtype=np.uint32))
mesh.commitParameters()

material = device.newMaterial('matte')
material.setParameter('color', anari.STRING, 'color')  # the vertex colours
material.commitParameters()
surface = device.newSurface()
surface.setParameter('geometry', anari.GEOMETRY, mesh)
surface.setParameter('material', anari.MATERIAL, material)
surface.commitParameters()

light = device.newLight('directional')
light.setParameter('direction', anari.float3, (0, 0, 1))
light.setParameter('irradiance', anari.float, 1)
light.commitParameters()

world = device.newWorld()
world.setParameterArray1D('surface', anari.SURFACE, [surface])
world.setParameterArray1D('light', anari.LIGHT, [light])
world.commitParameters()

renderer = device.newRenderer('default')
renderer.setParameter('pixelSamples', anari.INT32, 16)
renderer.setParameter('ambientRadiance', anari.FLOAT32, 0.3)
renderer.commitParameters()

frame = device.newFrame()
frame.setParameter('size', anari.uint2, (width, height))
frame.setParameter('channel.color', anari.DATA_TYPE, anari.UFIXED8_RGBA_SRGB)
frame.setParameter('renderer', anari.RENDERER, renderer)
frame.setParameter('camera', anari.CAMERA, camera)
frame.setParameter('world', anari.WORLD, world)
frame.commitParameters()
frame.render()

out = sys.argv[1] if len(sys.argv) > 1 else 'first_light.png'
write_png(out, frame.get('channel.color')[::-1])  # ANARI's rows go bottom-up
print(f'saved {out}')
