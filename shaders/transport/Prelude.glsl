// The GLSL side of the shared light-transport source (shaders/transport/, which
// docs/transport.md explains): the qualifiers that C++ spells as references, and the uniform
// declarations that C++ makes struct members (filters/CloudTransport.h defines the same three
// macros for C++). The mapper splices this file, then the shared files in their order
// (Medium.glsl names it), then Accessors.glsl.
#define INOUT(T) inout T
#define OUT(T) out T
#define UNIFORM uniform
