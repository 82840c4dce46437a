/* The temporary output files of greenconv's column writer (src/greenconv/io/files.f90):
 * created exclusively, written with every write(2) checked, removed on SIGINT and SIGTERM.
 *
 * The writer writes every output file to a temporary name (<out>.<pid>.<n>.part) and
 * renames it when complete.  It writes through these functions rather than Fortran I/O
 * because gfortran's runtime drops the error of a buffered write on a full disk (ENOSPC):
 * the WRITE, FLUSH and CLOSE statements all report success for the lost bytes.
 *
 * Each temporary file open is recorded in a fixed table here; a program that calls
 * gc_part_remove_on_signals() (the driver does) gets a handler that unlinks the recorded
 * files and then dies of the same signal, so an interrupted run leaves neither a .part file
 * nor a half-written output.
 *
 * The handler only reads the table and calls unlink(2), both async-signal-safe.  A slot is
 * claimed with an atomic exchange, filled, and only then marked ready, so the handler never
 * sees a half-copied name.  A name longer than the table holds is simply not recorded (the
 * writer then relies on its name pattern to be recognised as stale).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stddef.h>
#include <string.h>
#include <unistd.h>

#define GC_PART_SLOTS 64
#define GC_PART_LENGTH 4096

static char part_paths[GC_PART_SLOTS][GC_PART_LENGTH];
static volatile sig_atomic_t part_ready[GC_PART_SLOTS];
static int part_claimed[GC_PART_SLOTS];

/* Record a temporary file; returns its slot (>= 0), or -1 when the table is full or the
 * name too long. */
int gc_part_register(const char *path)
{
    size_t length = strlen(path);
    int slot;

    if (length >= GC_PART_LENGTH) return -1;
    for (slot = 0; slot < GC_PART_SLOTS; ++slot) {
        if (__atomic_exchange_n(&part_claimed[slot], 1, __ATOMIC_ACQ_REL) == 0) {
            memcpy(part_paths[slot], path, length + 1);
            __atomic_signal_fence(__ATOMIC_SEQ_CST);
            part_ready[slot] = 1;
            return slot;
        }
    }
    return -1;
}

/* Forget a slot of gc_part_register (the file was renamed or deleted). */
void gc_part_release(int slot)
{
    if (slot < 0 || slot >= GC_PART_SLOTS) return;
    part_ready[slot] = 0;
    __atomic_signal_fence(__ATOMIC_SEQ_CST);
    __atomic_store_n(&part_claimed[slot], 0, __ATOMIC_RELEASE);
}

static void remove_parts(int signal_number)
{
    int slot;

    for (slot = 0; slot < GC_PART_SLOTS; ++slot) {
        if (part_ready[slot]) unlink(part_paths[slot]);
    }
    /* Die of the same signal, so the parent sees what happened. */
    signal(signal_number, SIG_DFL);
    raise(signal_number);
}

/* Install the handler for SIGINT and SIGTERM, except where the signal is ignored (nohup,
 * a background job) or already handled by the host program.  Returns 0, or -1 when
 * sigaction failed. */
int gc_part_remove_on_signals(void)
{
    static const int signals[2] = {SIGINT, SIGTERM};
    struct sigaction action, previous;
    int i;

    memset(&action, 0, sizeof action);
    action.sa_handler = remove_parts;
    sigemptyset(&action.sa_mask);
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    for (i = 0; i < 2; ++i) {
        if (sigaction(signals[i], NULL, &previous) != 0) return -1;
        if (previous.sa_handler != SIG_DFL) continue;
        if (sigaction(signals[i], &action, NULL) != 0) return -1;
    }
    return 0;
}

/* Create a new file for writing, exclusively: fails with EEXIST when the name exists, even
 * as a dangling symlink (O_CREAT | O_EXCL never follows one).  Returns the descriptor, or
 * -errno. */
int gc_part_create(const char *path)
{
    int fd;

    do {
        fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0666);
    } while (fd < 0 && errno == EINTR);
    return fd >= 0 ? fd : -errno;
}

/* Whether a result of gc_part_create says that the name exists (EEXIST): 1 or 0. */
int gc_part_name_taken(int result)
{
    return result == -EEXIST;
}

/* Write all `length` bytes; returns 0 or the errno of the failed write(2). */
int gc_part_write(int fd, const char *bytes, size_t length)
{
    while (length > 0) {
        ssize_t written = write(fd, bytes, length);
        if (written < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        if (written == 0) return EIO;
        bytes += written;
        length -= (size_t)written;
    }
    return 0;
}

/* Close a descriptor; returns 0 or errno (NFS and some file systems report a lost write
 * only here). */
int gc_part_close(int fd)
{
    return close(fd) == 0 ? 0 : errno;
}

/* The text of an errno value, copied into `text` (at most `length` bytes, NUL-terminated). */
void gc_part_strerror(int number, char *text, size_t length)
{
    const char *message = strerror(number);
    size_t n = strlen(message);

    if (length == 0) return;
    if (n >= length) n = length - 1;
    memcpy(text, message, n);
    text[n] = '\0';
}
