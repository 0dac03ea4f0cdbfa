// The executable of a static test: everything it checks happened at compile time.
int main() { return 0; }
