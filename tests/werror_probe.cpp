// Deliberately warns (-Wconversion): the werror_probe test builds this and
// expects failure whenever SOUNDPAINT_WERROR is on, proving that the flag
// reaches the compiler rather than being silently dropped.
int narrow(double value) {
  int truncated = value;
  return truncated;
}
