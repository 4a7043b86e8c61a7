// tinygltf's implementation, compiled here from Debian's header (libtinygltf-dev) rather than
// linked from its libtinygltf.so: libdraco (render/gltf_decompress.h) carries a tinygltf of its own,
// another version with another class layout, and whichever copy the linker meets first would
// serve every call. Compiled into insitu's render stage, tinygltf is defined before the linker
// reaches Draco's archive, so only Draco's decoder objects are taken from it. Images are decoded by
// OpenImageIO (render/gltf_materials.h), never by tinygltf's stb_image: TINYGLTF_NO_STB_IMAGE and
// _WRITE are set for the whole stage (CMakeLists.txt).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
