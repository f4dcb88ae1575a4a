/* ANARI 1.0 enumerations: data types, status severities and codes, wait masks, log levels.
   Names and values are those of the Khronos standard, so code written against either header compiles. */
#pragma once

#include <stdint.h>

typedef int ANARIDataType;
typedef int ANARIStatusSeverity;
typedef int ANARIStatusCode;
typedef int ANARILogLevel;
typedef uint32_t ANARIWaitMask;

/* ANARIDataType. Numeric types come in blocks of four: scalar, VEC2, VEC3, VEC4. */
#define ANARI_UNKNOWN                    0

#define ANARI_DATA_TYPE                  100
#define ANARI_STRING                     101
#define ANARI_VOID_POINTER               102
#define ANARI_BOOL                       103
#define ANARI_STRING_LIST                150
#define ANARI_DATA_TYPE_LIST             151
#define ANARI_PARAMETER_LIST             152

#define ANARI_FUNCTION_POINTER           200
#define ANARI_MEMORY_DELETER             201
#define ANARI_STATUS_CALLBACK            202
#define ANARI_FRAME_COMPLETION_CALLBACK  203

#define ANARI_LIBRARY                    500
#define ANARI_DEVICE                     501
#define ANARI_OBJECT                     502
#define ANARI_ARRAY                      503
#define ANARI_ARRAY1D                    504
#define ANARI_ARRAY2D                    505
#define ANARI_ARRAY3D                    506
#define ANARI_CAMERA                     507
#define ANARI_FRAME                      508
#define ANARI_GEOMETRY                   509
#define ANARI_GROUP                      510
#define ANARI_INSTANCE                   511
#define ANARI_LIGHT                      512
#define ANARI_MATERIAL                   513
#define ANARI_RENDERER                   514
#define ANARI_SURFACE                    515
#define ANARI_SAMPLER                    516
#define ANARI_SPATIAL_FIELD              517
#define ANARI_VOLUME                     518
#define ANARI_WORLD                      519

#define ANARI_INT8                       1000
#define ANARI_INT8_VEC2                  1001
#define ANARI_INT8_VEC3                  1002
#define ANARI_INT8_VEC4                  1003

#define ANARI_UINT8                      1004
#define ANARI_UINT8_VEC2                 1005
#define ANARI_UINT8_VEC3                 1006
#define ANARI_UINT8_VEC4                 1007

#define ANARI_INT16                      1008
#define ANARI_INT16_VEC2                 1009
#define ANARI_INT16_VEC3                 1010
#define ANARI_INT16_VEC4                 1011

#define ANARI_UINT16                     1012
#define ANARI_UINT16_VEC2                1013
#define ANARI_UINT16_VEC3                1014
#define ANARI_UINT16_VEC4                1015

#define ANARI_INT32                      1016
#define ANARI_INT32_VEC2                 1017
#define ANARI_INT32_VEC3                 1018
#define ANARI_INT32_VEC4                 1019

#define ANARI_UINT32                     1020
#define ANARI_UINT32_VEC2                1021
#define ANARI_UINT32_VEC3                1022
#define ANARI_UINT32_VEC4                1023

#define ANARI_INT64                      1024
#define ANARI_INT64_VEC2                 1025
#define ANARI_INT64_VEC3                 1026
#define ANARI_INT64_VEC4                 1027

#define ANARI_UINT64                     1028
#define ANARI_UINT64_VEC2                1029
#define ANARI_UINT64_VEC3                1030
#define ANARI_UINT64_VEC4                1031

#define ANARI_FIXED8                     1032
#define ANARI_FIXED8_VEC2                1033
#define ANARI_FIXED8_VEC3                1034
#define ANARI_FIXED8_VEC4                1035

#define ANARI_UFIXED8                    1036
#define ANARI_UFIXED8_VEC2               1037
#define ANARI_UFIXED8_VEC3               1038
#define ANARI_UFIXED8_VEC4               1039

#define ANARI_FIXED16                    1040
#define ANARI_FIXED16_VEC2               1041
#define ANARI_FIXED16_VEC3               1042
#define ANARI_FIXED16_VEC4               1043

#define ANARI_UFIXED16                   1044
#define ANARI_UFIXED16_VEC2              1045
#define ANARI_UFIXED16_VEC3              1046
#define ANARI_UFIXED16_VEC4              1047

#define ANARI_FIXED32                    1048
#define ANARI_FIXED32_VEC2               1049
#define ANARI_FIXED32_VEC3               1050
#define ANARI_FIXED32_VEC4               1051

#define ANARI_UFIXED32                   1052
#define ANARI_UFIXED32_VEC2              1053
#define ANARI_UFIXED32_VEC3              1054
#define ANARI_UFIXED32_VEC4              1055

#define ANARI_FIXED64                    1056
#define ANARI_FIXED64_VEC2               1057
#define ANARI_FIXED64_VEC3               1058
#define ANARI_FIXED64_VEC4               1059

#define ANARI_UFIXED64                   1060
#define ANARI_UFIXED64_VEC2              1061
#define ANARI_UFIXED64_VEC3              1062
#define ANARI_UFIXED64_VEC4              1063

#define ANARI_FLOAT16                    1064
#define ANARI_FLOAT16_VEC2               1065
#define ANARI_FLOAT16_VEC3               1066
#define ANARI_FLOAT16_VEC4               1067

#define ANARI_FLOAT32                    1068
#define ANARI_FLOAT32_VEC2               1069
#define ANARI_FLOAT32_VEC3               1070
#define ANARI_FLOAT32_VEC4               1071

#define ANARI_FLOAT64                    1072
#define ANARI_FLOAT64_VEC2               1073
#define ANARI_FLOAT64_VEC3               1074
#define ANARI_FLOAT64_VEC4               1075

#define ANARI_UFIXED8_R_SRGB             2000
#define ANARI_UFIXED8_RA_SRGB            2001
#define ANARI_UFIXED8_RGB_SRGB           2002
#define ANARI_UFIXED8_RGBA_SRGB          2003

#define ANARI_INT32_BOX1                 2004
#define ANARI_INT32_BOX2                 2005
#define ANARI_INT32_BOX3                 2006
#define ANARI_INT32_BOX4                 2007

#define ANARI_FLOAT32_BOX1               2008
#define ANARI_FLOAT32_BOX2               2009
#define ANARI_FLOAT32_BOX3               2010
#define ANARI_FLOAT32_BOX4               2011

#define ANARI_FLOAT32_MAT2               2012
#define ANARI_FLOAT32_MAT3               2013
#define ANARI_FLOAT32_MAT4               2014
#define ANARI_FLOAT32_MAT2x3             2015

#define ANARI_FLOAT32_MAT3x4             2016
#define ANARI_FLOAT32_QUAT_IJKW          2017

#define ANARI_UINT64_REGION1             2104
#define ANARI_UINT64_REGION2             2105
#define ANARI_UINT64_REGION3             2106
#define ANARI_UINT64_REGION4             2107

#define ANARI_FLOAT64_BOX1               2208
#define ANARI_FLOAT64_BOX2               2209
#define ANARI_FLOAT64_BOX3               2210
#define ANARI_FLOAT64_BOX4               2211

/* ANARIWaitMask */
#define ANARI_NO_WAIT 0
#define ANARI_WAIT    1

/* ANARIStatusSeverity */
#define ANARI_SEVERITY_FATAL_ERROR         1
#define ANARI_SEVERITY_ERROR               2
#define ANARI_SEVERITY_WARNING             3
#define ANARI_SEVERITY_PERFORMANCE_WARNING 4
#define ANARI_SEVERITY_INFO                5
#define ANARI_SEVERITY_DEBUG               6

/* ANARIStatusCode */
#define ANARI_STATUS_NO_ERROR           0
#define ANARI_STATUS_UNKNOWN_ERROR      1
#define ANARI_STATUS_INVALID_ARGUMENT   2
#define ANARI_STATUS_INVALID_OPERATION  3
#define ANARI_STATUS_OUT_OF_MEMORY      4
#define ANARI_STATUS_UNSUPPORTED_DEVICE 5
#define ANARI_STATUS_VERSION_MISMATCH   6

/* ANARILogLevel */
#define ANARI_LOG_DEBUG   1
#define ANARI_LOG_INFO    2
#define ANARI_LOG_WARNING 3
#define ANARI_LOG_ERROR   4
#define ANARI_LOG_NONE    5
