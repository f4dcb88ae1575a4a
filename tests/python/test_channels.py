"""Every frame channel as a numpy array of the right shape and dtype."""
import numpy as np
import pytest
import pynari as anari

import scenes

H, W = scenes.SIZE[1], scenes.SIZE[0]


@pytest.fixture(scope='module')
def frame(device):
    world = scenes.world(device, [scenes.surface(device, scenes.triangles(device))])
    f = scenes.frame(device, world, channels={
        'channel.depth': anari.FLOAT32, 'channel.albedo': anari.FLOAT32_VEC3,
        'channel.normal': anari.FLOAT32_VEC3, 'channel.primitiveId': anari.UINT32,
        'channel.objectId': anari.UINT32, 'channel.instanceId': anari.UINT32})
    f.render()
    return f


@pytest.mark.parametrize('channel,shape,dtype', [
    ('channel.color', (H, W, 4), np.uint8),
    ('channel.depth', (H, W), np.float32),
    ('channel.albedo', (H, W, 3), np.float32),
    ('channel.normal', (H, W, 3), np.float32),
    ('channel.primitiveId', (H, W), np.uint32),
    ('channel.objectId', (H, W), np.uint32),
    ('channel.instanceId', (H, W), np.uint32),
])
def test_channel_shape_and_dtype(frame, channel, shape, dtype):
    image = frame.get(channel)
    assert image.shape == shape and image.dtype == dtype


def test_channels_agree(frame):
    depth = frame.get('channel.depth')
    prim = frame.get('channel.primitiveId')
    hit = np.isfinite(depth) & (depth < 1e30)
    assert hit.any() and (~hit).any()
    assert set(np.unique(prim[hit])) <= {0, 1}  # the quad's two triangles
    assert np.all(prim[~hit] == 0xFFFFFFFF)
    assert scenes.not_blank(frame.get('channel.color'))


def test_float_color(device):
    world = scenes.world(device, [scenes.surface(device, scenes.triangles(device))])
    f = scenes.frame(device, world, channels={'channel.color': anari.FLOAT32_VEC4})
    f.render()
    color = f.get('channel.color')
    assert color.shape == (H, W, 4) and color.dtype == np.float32 and color[..., :3].max() > 0.05


def test_channel_not_rendered_is_an_error(device):
    world = scenes.world(device, [])
    f = scenes.frame(device, world)
    f.render()
    # The device's own text when it reports one (Ripple does), else the module's ValueError.
    with pytest.raises((anari.DeviceError, ValueError), match='channel.depth'):
        f.get('channel.depth')
