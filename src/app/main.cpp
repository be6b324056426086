#include <cstdio>
int main() { std::puts("rigidflex " RIGIDFLEX_VERSION); return 0; }
