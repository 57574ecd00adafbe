/* The entry point of a tessera application: a program written against
 * OpenGL ES 1.1 and EGL 1.4 that runs on the simulated SoC's host.
 *
 *   soc_sim --app ./libmine.so [-- arg ...]
 *
 * loads the shared library, calls tessera_app_main with the arguments after
 * "--" (argv[0] is the library's path) and ends the simulation after
 * --frames calls of eglSwapBuffers (the last one does not return) or when
 * tessera_app_main returns. Return 0 on success, 2 for a bad input (a file
 * that cannot be read, a bad argument), anything else for a failure.
 *
 * An ordinary program needs neither this header nor this function: a
 * library without tessera_app_main that defines int main(int argc, char**
 * argv) has its main called the same way. With both, tessera_app_main is
 * the one called. */
#ifndef TESSERA_APP_H
#define TESSERA_APP_H

#ifdef __cplusplus
extern "C" {
#endif

/* Exported even when the application is built with -fvisibility=hidden. */
__attribute__((visibility("default"))) int tessera_app_main(int argc, char** argv);

#ifdef __cplusplus
}
#endif

#endif
