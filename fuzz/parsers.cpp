// TinyGLTF's and tinyobjloader's implementations for the fuzz build (TESSERA_FUZZ), compiled
// from Debian's headers so that libFuzzer sees their branches and the sanitizers their memory
// accesses. The normal build links Debian's shared libraries instead. stb_image and
// stb_image_write are implemented in core/image.cpp.
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
