// tinyobjloader's parser (header-only code, the same version as the Debian library the program links)
// compiled into the fuzz targets: the executable's own definitions win over the shared library's, so
// libFuzzer is guided by the branches of the OBJ and MTL parser too and ASan checks its memory accesses.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
