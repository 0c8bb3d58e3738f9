// A full disk for one process, without a small file system or root: loaded with LD_PRELOAD, it
// lets CLOUDVIS_TEST_WRITE_LIMIT bytes in all reach regular files under the directory
// CLOUDVIS_TEST_WRITE_DIR (default: the working directory at start-up) whose path ends with
// CLOUDVIS_TEST_WRITE_SUFFIX (when set), and then fails every
// further write to them as a full disk does: the write that crosses the limit is cut short, the
// next ones fail with ENOSPC. With CLOUDVIS_TEST_FAIL_FSYNC set, fsync and fdatasync of those
// files fail with EIO instead (a write-back error reported late, as NFS or a failing disk
// does). Standard output, standard error, pipes and files elsewhere (shader caches) are not
// touched. It interposes the calls through which bytes reach a file: write, writev, pwrite and
// pwritev (what libstdc++'s streams and cloudvis call) and fwrite (what libpng and zlib call;
// glibc's own stdio flushes reach the kernel through internal calls no preload can see).
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

static pthread_mutex_t Lock = PTHREAD_MUTEX_INITIALIZER;
static char Directory[PATH_MAX];
static const char* Suffix = NULL;
static long long Remaining = -1; // bytes still allowed; -1: no limit set
static int FailFsync = 0;

__attribute__((constructor)) static void Start(void)
{
  const char* limit = getenv("CLOUDVIS_TEST_WRITE_LIMIT");
  const char* directory = getenv("CLOUDVIS_TEST_WRITE_DIR");
  if (limit && *limit)
  {
    Remaining = atoll(limit);
  }
  FailFsync = getenv("CLOUDVIS_TEST_FAIL_FSYNC") != NULL;
  Suffix = getenv("CLOUDVIS_TEST_WRITE_SUFFIX");
  if (directory && *directory)
  {
    if (!realpath(directory, Directory))
    {
      snprintf(Directory, sizeof(Directory), "%s", directory);
    }
  }
  else if (!getcwd(Directory, sizeof(Directory)))
  {
    Directory[0] = '\0';
  }
}

// True when `fd` is a regular file under Directory.
static int Watched(int fd)
{
  struct stat info;
  if (Directory[0] == '\0' || fstat(fd, &info) != 0 || !S_ISREG(info.st_mode))
  {
    return 0;
  }
  char link[64], path[PATH_MAX];
  snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
  const ssize_t length = readlink(link, path, sizeof(path) - 1);
  if (length <= 0)
  {
    return 0;
  }
  path[length] = '\0';
  const size_t prefix = strlen(Directory);
  const size_t suffix = Suffix ? strlen(Suffix) : 0;
  return strncmp(path, Directory, prefix) == 0 && (path[prefix] == '/' || path[prefix] == '\0') &&
    (size_t)length >= suffix && strcmp(path + length - suffix, Suffix ? Suffix : "") == 0;
}

// How many of `count` bytes to `fd` may be written: all when unwatched, else what the limit
// leaves (taken from it); 0 means "fail with ENOSPC".
static size_t Allowed(int fd, size_t count)
{
  if (Remaining < 0 || count == 0 || !Watched(fd))
  {
    return count;
  }
  pthread_mutex_lock(&Lock);
  const size_t allowed = (long long)count < Remaining ? count : (size_t)Remaining;
  Remaining -= (long long)allowed;
  pthread_mutex_unlock(&Lock);
  return allowed;
}

#define REAL(name, type) ((type)dlsym(RTLD_NEXT, name))

ssize_t write(int fd, const void* data, size_t count)
{
  const size_t allowed = Allowed(fd, count);
  if (allowed == 0 && count > 0)
  {
    errno = ENOSPC;
    return -1;
  }
  return REAL("write", ssize_t(*)(int, const void*, size_t))(fd, data, allowed);
}

ssize_t pwrite(int fd, const void* data, size_t count, off_t offset)
{
  const size_t allowed = Allowed(fd, count);
  if (allowed == 0 && count > 0)
  {
    errno = ENOSPC;
    return -1;
  }
  return REAL("pwrite", ssize_t(*)(int, const void*, size_t, off_t))(fd, data, allowed, offset);
}

ssize_t pwrite64(int fd, const void* data, size_t count, off_t offset)
{
  return pwrite(fd, data, count, offset);
}

// The vector's first `allowed` bytes, written one piece at a time (short writes are allowed).
static ssize_t WriteVector(int fd, const struct iovec* pieces, int n, off_t offset, int positioned)
{
  size_t total = 0;
  for (int i = 0; i < n; ++i)
  {
    total += pieces[i].iov_len;
  }
  size_t allowed = Allowed(fd, total);
  if (allowed == 0 && total > 0)
  {
    errno = ENOSPC;
    return -1;
  }
  ssize_t written = 0;
  for (int i = 0; i < n && allowed > 0; ++i)
  {
    const size_t length = pieces[i].iov_len < allowed ? pieces[i].iov_len : allowed;
    const ssize_t done = positioned
      ? REAL("pwrite", ssize_t(*)(int, const void*, size_t, off_t))(
          fd, pieces[i].iov_base, length, offset + written)
      : REAL("write", ssize_t(*)(int, const void*, size_t))(fd, pieces[i].iov_base, length);
    if (done < 0)
    {
      return written > 0 ? written : -1;
    }
    written += done;
    allowed -= (size_t)done;
    if ((size_t)done < length)
    {
      break;
    }
  }
  return written;
}

ssize_t writev(int fd, const struct iovec* pieces, int n)
{
  return WriteVector(fd, pieces, n, 0, 0);
}

ssize_t pwritev(int fd, const struct iovec* pieces, int n, off_t offset)
{
  return WriteVector(fd, pieces, n, offset, 1);
}

size_t fwrite(const void* data, size_t size, size_t n, FILE* stream)
{
  size_t (*real)(const void*, size_t, size_t, FILE*) =
    REAL("fwrite", size_t(*)(const void*, size_t, size_t, FILE*));
  if (size == 0 || n == 0 || Remaining < 0)
  {
    return real(data, size, n, stream);
  }
  const size_t allowed = Allowed(fileno(stream), size * n);
  const size_t whole = allowed / size;
  const size_t done = whole > 0 ? real(data, size, whole, stream) : 0;
  if (done < n)
  {
    errno = ENOSPC;
  }
  return done;
}

static int FsyncFails(int fd)
{
  if (FailFsync && Watched(fd))
  {
    errno = EIO;
    return 1;
  }
  return 0;
}

int fsync(int fd)
{
  return FsyncFails(fd) ? -1 : REAL("fsync", int (*)(int))(fd);
}

int fdatasync(int fd)
{
  return FsyncFails(fd) ? -1 : REAL("fdatasync", int (*)(int))(fd);
}
