// Host code (builders, edits, loaders) is either compiled in every file that uses it
// (header-only, the default) or once, in the voxray::kernels library, which a program
// links instead. Its out-of-line definitions live in a module's detail/ headers, marked
// VOXRAY_HOST_INLINE, and the public header includes them only where
// VOXRAY_HOST_DEFINITIONS is 1:
//
//   file                              defined                 definitions     VOXRAY_HOST_INLINE
//   header-only use (the default)     nothing                 seen, inline    inline
//   a target linking voxray::kernels  VOXRAY_HOST_LINKED      not seen        (empty)
//   the library's generated host.cpp  VOXRAY_HOST_COMPILING   seen, the one   (empty)
//
// A program links voxray::kernels in every target that uses the host code, or in none:
// the two modes give the same functions, one inline and one not.
#pragma once

#if defined(VOXRAY_HOST_COMPILING)
#define VOXRAY_HOST_DEFINITIONS 1
#define VOXRAY_HOST_INLINE
#elif defined(VOXRAY_HOST_LINKED)
#define VOXRAY_HOST_DEFINITIONS 0
#define VOXRAY_HOST_INLINE
#else
#define VOXRAY_HOST_DEFINITIONS 1
#define VOXRAY_HOST_INLINE inline
#endif
