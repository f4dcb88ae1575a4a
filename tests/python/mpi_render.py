"""Data-parallel rendering from Python: each rank creates only its share of the spheres (sphere i on rank
i % size), the frame is rendered collectively, and rank 0 saves or compares the image.
Usage: mpirun -np N python3 mpi_render.py save|compare IMAGE.npy"""
import os
import sys

from mpi4py import MPI  # initialises MPI before the device is made
import numpy as np
import pynari as anari

sys.path.insert(0, os.path.dirname(__file__))
import scenes  # noqa: E402

mode, path = sys.argv[1], sys.argv[2]
comm = MPI.COMM_WORLD
rank, size = comm.Get_rank(), comm.Get_size()
device = anari.newDevice('default')
device.setParameter('pointer_to_mpi_communicator', anari.UINT64, MPI._addressof(comm))  # pynari's sample06 way
device.commitParameters()

centers = [(x, y, 0.0) for x in (-0.7, 0.0, 0.7) for y in (-0.4, 0.4)]
mine = [c for i, c in enumerate(centers) if i % size == rank]
surfaces = [scenes.surface(device, scenes.spheres(device, mine))] if mine else []
frame = scenes.frame(device, scenes.world(device, surfaces, light=(rank == 0)), samples=4)
frame.render()
image = frame.get('channel.color')
if rank == 0:
    if mode == 'save':
        np.save(path, image)
    else:
        reference = np.load(path)
        difference = np.abs(image.astype(int) - reference.astype(int)).max()
        print(f'{size} ranks against 1: largest difference {difference}')
        assert scenes.not_blank(image)
        assert difference == 0, f'the {size}-rank image differs from the 1-rank image by up to {difference}'
