/*
 * Temporary output files and signals (src/greenconv/io/part_files.c, used by the driver):
 * a process that installed the handler and has a temporary file recorded dies of SIGTERM or
 * SIGINT with the file removed; a name that exists (a planted symlink) is never created over.
 * These are the library's internal functions, declared here (not in greenconv.h).
 */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>
#include "check.h"

int gc_part_create(const char *path);
int gc_part_register(const char *path);
int gc_part_remove_on_signals(void);
int gc_part_name_taken(int result);
int gc_part_write(int fd, const char *bytes, size_t length);

/* A child with a recorded temporary file, killed by `signal_number`. */
static void interrupted_child(int signal_number, const char *name)
{
    char path[256], what[300];
    int ready[2], status = 0;
    pid_t child;

    snprintf(path, sizeof path, "build/ctest_part_%s_%ld.part", name, (long)getpid());
    if (pipe(ready) != 0) return;
    child = fork();
    if (child == 0) {
        int fd;
        /* A shell starts background jobs with SIGINT ignored, and the handler (rightly) leaves an
         * ignored signal alone: give the child the default disposition, as a terminal would. */
        signal(signal_number, SIG_DFL);
        gc_part_remove_on_signals();
        fd = gc_part_create(path);
        gc_part_register(path);
        gc_part_write(fd, "rows\n", 5);
        if (write(ready[1], "x", 1) != 1) _exit(9);
        for (;;) pause();
    }
    {
        char byte;
        if (read(ready[0], &byte, 1) != 1) byte = 0;
    }
    kill(child, signal_number);
    waitpid(child, &status, 0);
    snprintf(what, sizeof what, "%s: the child died of it and its temporary file is gone", name);
    check(WIFSIGNALED(status) && WTERMSIG(status) == signal_number && access(path, F_OK) != 0, what, path);
    unlink(path);
    close(ready[0]);
    close(ready[1]);
}

int main(void)
{
    const char *link_path = "build/ctest_part_planted.part";
    const char *target = "build/ctest_part_target.txt";
    FILE *file;
    char text[32] = "";
    int result;

    interrupted_child(SIGTERM, "SIGTERM");
    interrupted_child(SIGINT, "SIGINT");

    file = fopen(target, "w");
    if (file) {
        fputs("secret\n", file);
        fclose(file);
    }
    unlink(link_path);
    if (symlink("ctest_part_target.txt", link_path) != 0) perror("symlink");
    result = gc_part_create(link_path);
    file = fopen(target, "r");
    if (file) {
        if (!fgets(text, sizeof text, file)) text[0] = '\0';
        fclose(file);
    }
    check(result < 0 && gc_part_name_taken(result) && strcmp(text, "secret\n") == 0,
          "a planted symlink: refused as taken, its target untouched", text);
    unlink(link_path);
    unlink(target);
    return check_exit();
}
