/* The entry point of an application of its own (run_application.cpp):
 * tessera_app_main if the program defines it, else its main; null if
 * neither. In C, where a program may name main. ARM only. */
int tessera_app_main(int argc, char** argv) __attribute__((weak));
int main(int argc, char** argv) __attribute__((weak));

typedef int (*tessera_entry)(int argc, char** argv);

tessera_entry tessera_application_entry(void) {
  return tessera_app_main ? tessera_app_main : main;
}
