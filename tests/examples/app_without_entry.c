/* A well-formed shared library that is not a tessera application: it has
 * neither tessera_app_main nor main. */
int not_an_application(void) {
  return 0;
}
