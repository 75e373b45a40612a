// Placeholder: filled in by the mesh-preparation work.
#include "Remeshing.h"
