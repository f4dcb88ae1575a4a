/* Compiled as C (with the project's pedantic warnings as errors): anari.h must be a valid C header, and C
   code must be able to pass any handle where an ANARIObject is expected. */
#include "anari/anari.h"

int loadertestCHeaderValues(void) {
    ANARIArray1D array = ANARI_INVALID_HANDLE;
    ANARIObject asObject = array;
    ANARIParameterValue initializers[1] = {{NULL, ANARI_UNKNOWN, NULL}};
    ANARIDataType type = ANARI_FLOAT32_VEC3;
    ANARIWaitMask mask = ANARI_WAIT;
    (void)asObject;
    (void)initializers;
    return type + (int)mask;
}
