/* read_file.h -- a whole file into memory, and a file's date, for the
 * launcher.
 *
 * bk_read_file(path, len)
 *   path in   the file
 *   len  out  its size in bytes
 * Returns the bytes with a NUL after them (malloc'd: the caller frees them),
 * or NULL when the file cannot be read or memory runs out.
 *
 * bk_mtime_ns(dir, name)
 *   dir, name in   the file DIR/NAME
 * Returns its modification time in nanoseconds since the epoch, or -1 when it
 * cannot be read.
 *
 * bk_stat_ns(st)
 *   st   in   a stat(2) result
 * Returns its modification time in nanoseconds since the epoch (the unit of
 * the run cache's entries). */
#ifndef BK_READ_FILE_H
#define BK_READ_FILE_H

#include <stddef.h>
#include <sys/stat.h>

char *bk_read_file(const char *path, size_t *len);
long long bk_mtime_ns(const char *dir, const char *name);
long long bk_stat_ns(const struct stat *st);

#endif
