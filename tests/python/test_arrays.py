"""Every array element type from numpy, in 1 to 3 dimensions; object arrays from lists; wrong input."""
import numpy as np
import pytest
import pynari as anari

# (constant, numpy dtype, components)
NUMERIC = []
for base, dtype in (('INT8', np.int8), ('UINT8', np.uint8), ('INT16', np.int16), ('UINT16', np.uint16),
                    ('INT32', np.int32), ('UINT32', np.uint32), ('INT64', np.int64), ('UINT64', np.uint64),
                    ('FIXED8', np.int8), ('UFIXED8', np.uint8), ('FIXED16', np.int16), ('UFIXED16', np.uint16),
                    ('FLOAT32', np.float32), ('FLOAT64', np.float64)):
    NUMERIC.append((base, dtype, 1))
    for n in (2, 3, 4):
        NUMERIC.append((f'{base}_VEC{n}', dtype, n))
NUMERIC += [('UFIXED8_RGBA_SRGB', np.uint8, 4), ('UFIXED8_RGB_SRGB', np.uint8, 3),
            ('FLOAT32_BOX1', np.float32, 2), ('FLOAT32_BOX3', np.float32, 6), ('INT32_BOX2', np.int32, 4),
            ('FLOAT32_MAT4', np.float32, 16), ('FLOAT32_MAT3x4', np.float32, 12)]


@pytest.mark.parametrize('name,dtype,components', NUMERIC, ids=[n[0] for n in NUMERIC])
def test_every_numeric_type_in_every_dimension(device, name, dtype, components):
    type_ = getattr(anari, name)
    tail = (components,) if components > 1 else ()
    for dims, make in ((1, device.newArray1D), (2, device.newArray2D), (3, device.newArray3D)):
        grid = (2, 3, 4)[:dims]
        array = make(type_, np.zeros(grid + tail, dtype=dtype))
        assert array.type == getattr(anari, f'ARRAY{dims}D')
    # the flat form of pynari's samples: n*components numbers for n elements
    device.newArray1D(type_, np.zeros(5 * components, dtype=dtype))


def test_object_arrays_from_lists(device):
    lights = [device.newLight('directional') for _ in range(3)]
    array = device.newArray1D(anari.LIGHT, lights)
    assert array.type == anari.ARRAY1D
    device.newArray(anari.LIGHT, tuple(lights))  # pynari's older spelling
    world = device.newWorld()
    world.setParameter('light', anari.ARRAY1D, array)
    world.commitParameters()


def test_non_contiguous_arrays_are_copied(device):
    data = np.arange(24, dtype=np.float32).reshape(4, 6)[:, ::2]  # a strided view
    assert not data.flags['C_CONTIGUOUS']
    device.newArray2D(anari.FLOAT32, data)


def test_wrong_dtype_is_a_type_error(device):
    with pytest.raises(TypeError, match='FLOAT32_VEC3.*float32.*float64'):
        device.newArray1D(anari.FLOAT32_VEC3, np.zeros(9))


def test_wrong_shape_is_a_value_error(device):
    with pytest.raises(ValueError, match=r'newArray1D\(FLOAT32_VEC3\).*\(7,\)'):
        device.newArray1D(anari.FLOAT32_VEC3, np.zeros(7, dtype=np.float32))
    with pytest.raises(ValueError, match=r'newArray2D\(FLOAT32_VEC4\)'):
        device.newArray2D(anari.FLOAT32_VEC4, np.zeros((2, 3), dtype=np.float32))
    with pytest.raises(ValueError, match=r'newArray3D\(FLOAT32\)'):
        device.newArray3D(anari.FLOAT32, np.zeros((2, 3), dtype=np.float32))


def test_not_an_array_is_a_type_error(device):
    with pytest.raises(TypeError, match='numpy array'):
        device.newArray1D(anari.FLOAT32, [1.0, 2.0])
    with pytest.raises(TypeError, match='SURFACE.*LIGHT'):
        device.newArray1D(anari.SURFACE, [device.newLight('directional')])
    with pytest.raises(TypeError, match='pynari objects'):
        device.newArray1D(anari.SURFACE, [1, 2])
