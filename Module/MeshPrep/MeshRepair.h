#ifndef catarMeshRepair_h
#define catarMeshRepair_h
#include "TriangleMesh.h"
#endif
