"""Wrong types, values and device errors: Python exceptions and warnings naming what was wrong."""
import warnings

import pytest
import pynari as anari


def test_parameter_type_errors_name_the_parameter(device):
    cam = device.newCamera('perspective')
    with pytest.raises(ValueError, match=r"'position', FLOAT32_VEC3.*3 number.*got 2"):
        cam.setParameter('position', anari.float3, (1, 2))
    with pytest.raises(TypeError, match=r"'position'.*str"):
        cam.setParameter('position', anari.float3, 'here')
    with pytest.raises(TypeError, match=r"'aspect'.*NoneType"):
        cam.setParameter('aspect', anari.FLOAT32, None)
    with pytest.raises(TypeError, match=r"'count'.*integers"):
        cam.setParameter('count', anari.INT32, 1.5)
    with pytest.raises(ValueError, match=r"'count'.*does not fit"):
        cam.setParameter('count', anari.UINT32, -1)
    with pytest.raises(ValueError, match=r"'count'.*does not fit"):
        cam.setParameter('count', anari.INT8, 300)
    surf = device.newSurface()
    with pytest.raises(TypeError, match=r"'geometry', GEOMETRY.*MATERIAL"):
        surf.setParameter('geometry', anari.GEOMETRY, device.newMaterial('matte'))
    with pytest.raises(TypeError, match=r"'geometry'.*pynari object"):
        surf.setParameter('geometry', anari.GEOMETRY, 3)
    with pytest.raises(TypeError, match=r"'name'.*str"):
        surf.setParameter('name', anari.STRING, 3)
    with pytest.raises(TypeError, match=r"'x'"):
        surf.setParameter('x', 2.0)  # no type: only objects and strings


def test_accepted_value_forms(device):
    inst = device.newInstance('transform')
    inst.setParameter('transform', anari.FLOAT32_MAT4, [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    import numpy as np
    inst.setParameter('transform', anari.FLOAT32_MAT4, np.eye(4))  # nested and float64: converted
    inst.setParameter('id', anari.UINT32, np.uint32(7))
    vol = device.newVolume('transferFunction1D')
    vol.setParameter('valueRange', anari.FLOAT32_BOX1, (0., 7.))
    mat = device.newMaterial('matte')
    mat.setParameter('color', 'color')  # pynari's string form without a type
    mat.setParameter('opacity', anari.float, 1)  # an int for a float


def test_device_errors_are_exceptions_with_the_device_text(device):
    frame = device.newFrame()
    frame.setParameter('size', anari.uint2, (8, 8))
    frame.commitParameters()
    with pytest.raises(anari.DeviceError) as error:
        frame.render()  # no renderer, camera or world
    assert 'frame.render()' in str(error.value) and len(str(error.value)) > len('frame.render(): ')
    assert isinstance(error.value, RuntimeError)


def test_device_warnings_are_python_warnings(device):
    mat = device.newMaterial('matte')
    mat.setParameter('notAParameterOfMatte', anari.FLOAT32, 1.0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always')
        mat.commitParameters()
    assert any(issubclass(w.category, anari.DeviceWarning) and 'notAParameterOfMatte' in str(w.message)
               for w in caught)


def test_unknown_library_is_a_device_error():
    with pytest.raises(anari.DeviceError, match='no_such_library'):
        anari.newDevice('no_such_library')


def test_introspection(device):
    assert 'default' in device.getObjectSubtypes(anari.RENDERER)
    info = device.getObjectInfo(anari.RENDERER, 'default')
    assert info['parameters'] and all('name' in p and 'type' in p for p in info['parameters'])
    p = info['parameters'][0]
    assert set(device.getParameterInfo(anari.RENDERER, 'default', p['name'], p['type'])) == {'description', 'required'}
