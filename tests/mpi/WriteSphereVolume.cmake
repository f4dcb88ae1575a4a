# Writes a 16^3 uint8 NRRD file (cmake -DOUT=file -P WriteSphereVolume.cmake) for the data-parallel
# ripple-render --volume tests: 122 - d2/4 at least 48, where d2 is the squared distance from the centre in
# half-samples, so every byte is printable text and the 85 surface is a sphere of radius about 6 samples.
set(bytes "")
foreach(z RANGE 15)
  foreach(y RANGE 15)
    foreach(x RANGE 15)
      math(EXPR v "122 - ((2*${x}-15)*(2*${x}-15) + (2*${y}-15)*(2*${y}-15) + (2*${z}-15)*(2*${z}-15)) / 4")
      if(v LESS 48)
        set(v 48)
      endif()
      string(ASCII ${v} c)
      string(APPEND bytes "${c}")
    endforeach()
  endforeach()
endforeach()
file(WRITE "${OUT}" "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: raw\n\n${bytes}")
