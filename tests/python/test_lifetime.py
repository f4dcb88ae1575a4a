"""Objects released by Python's garbage collector while the device still uses them."""
import gc
import sys

import numpy as np
import pynari as anari

import scenes


def render_quad(device, drop_references):
    positions = np.array([-1, -1, 0.5, 1, -1, 0.5, -1, 1, 0.5, 1, 1, 0.5], dtype=np.float32)
    mesh = device.newGeometry('triangle')
    mesh.setParameter('vertex.position', anari.ARRAY1D, device.newArray1D(anari.FLOAT32_VEC3, positions))
    mesh.setParameterArray1D('primitive.index', anari.UINT32_VEC3, np.array([0, 1, 2, 1, 3, 2], dtype=np.uint32))
    mesh.commitParameters()
    surf = scenes.surface(device, mesh)
    world = scenes.world(device, [surf])
    frame = scenes.frame(device, world)
    if drop_references:
        # Only the frame is left to Python: geometry, arrays, numpy data, material, surface, world, light,
        # camera and renderer live on inside the device.
        del positions, mesh, surf, world
        gc.collect()
    frame.render()
    return frame.get('channel.color')


def test_objects_collected_while_in_use_still_render(device):
    kept = render_quad(device, drop_references=False)
    dropped = render_quad(device, drop_references=True)
    assert scenes.not_blank(kept)
    assert np.array_equal(kept, dropped)


def test_shared_numpy_array_lives_until_the_device_lets_go():
    device = anari.newDevice('default')
    data = np.linspace(0, 1, 300, dtype=np.float32)
    before = sys.getrefcount(data)
    array = device.newArray1D(anari.FLOAT32_VEC3, data)
    assert sys.getrefcount(data) == before + 1  # the device's reference
    mesh = device.newGeometry('sphere')
    mesh.setParameter('vertex.position', anari.ARRAY1D, array)
    mesh.commitParameters()
    del array
    gc.collect()
    assert sys.getrefcount(data) == before + 1  # the geometry still uses it
    mesh.release()
    del device
    gc.collect()
    assert sys.getrefcount(data) == before


def test_device_outlives_its_python_handle():
    device = anari.newDevice('default')
    world = scenes.world(device, [scenes.surface(device, scenes.triangles(device))])
    frame = scenes.frame(device, world)
    del device, world
    gc.collect()
    frame.render()
    assert scenes.not_blank(frame.get('channel.color'))


def test_released_object_is_an_error_not_a_crash(device):
    mat = device.newMaterial('matte')
    mat.release()
    mat.release()  # twice is harmless
    try:
        mat.setParameter('color', anari.float3, (1, 0, 0))
    except ValueError as e:
        assert 'released' in str(e)
    else:
        raise AssertionError('no ValueError')
