// Arithmetic on path names, without touching the file system. Formats are recognised by
// extension without regard to case everywhere in cloudvis (a camera's FIELD.VTI, a Windows
// user's Cloud.Pvti, an IMAGE.PNG), so every comparison of extensions goes through
// LowerCaseExtension.
#ifndef cloudvis_FileNames_h
#define cloudvis_FileNames_h

#include <string>

namespace cloudvis
{

// The directory part of `path`: "." for a bare name, "/" for a name in the root.
std::string DirectoryOf(const std::string& path);

// The last component of `path` (everything after the last '/').
std::string FileNameOf(const std::string& path);

// The extension of the last component, dot included, in lower case (ASCII letters only):
// ".vti" for "dir/Field.VTI", "" for "README", ".bashrc" or "dir.d/file". A leading dot marks a
// hidden file, not an extension.
std::string LowerCaseExtension(const std::string& path);

} // namespace cloudvis

#endif
