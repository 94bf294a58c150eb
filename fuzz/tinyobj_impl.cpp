// tinyobjloader's implementation, built with the fuzz flags (see CMakeLists.txt):
// an instrumented copy of the parser the OBJ and scene fuzzers reach.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
