// tinygltf's implementation, compiled here only for the fuzz build
// (SOUNDPAINT_FUZZ): Debian ships tinygltf as an uninstrumented shared
// library, inside which the fuzzer could neither see coverage nor catch
// memory errors. Images are never decoded by soundpaint, so stb_image is
// only declared (Debian's libstb provides it).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
