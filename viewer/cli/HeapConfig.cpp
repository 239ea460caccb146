// csgray's heap: jemalloc, linked in place of glibc's malloc (viewer/CMakeLists.txt), reads this
// configuration when it starts.
//
// thp:always: jemalloc advises all its memory onto transparent huge pages (MADV_HUGEPAGE, which
// the kernel honours in its "madvise" and "always" modes), so first touching fresh memory costs
// a page fault per 2 MiB instead of per 4 KiB. Mesh export fills and grows arrays of hundreds of
// megabytes, and a fault is costly on a virtual machine: on csg_grid3 this cut the export's
// faults and its time markedly (bench/README.md, csgray's heap on huge pages).
// glibc's malloc can do the same only when told by the GLIBC_TUNABLES environment variable.
// metadata_thp:auto: jemalloc's own metadata too, once it grows large.
extern "C" {
extern const char* malloc_conf;
const char* malloc_conf = "thp:always,metadata_thp:auto";
}
