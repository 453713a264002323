#include <cstdio>
int main() { std::puts("skyspec: under construction"); return 0; }
