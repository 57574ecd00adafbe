/* A well-formed shared library that is not a tessera application: it has
 * no tessera_app_main. */
int not_an_application(void) {
  return 0;
}
