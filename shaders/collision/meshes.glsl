// The meshes of a collision pass (SSBO 8, MeshInfo per mesh): where each mesh's faces, leaf-box
// rows and vertex positions lie. One declaration for every collision shader (an include is
// expanded once per shader).
#include "common/layout.glsl"

layout(std430, binding = BINDING_MESH_INFO) readonly buffer MeshInfos {
  MeshInfo meshes[];
};
