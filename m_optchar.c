#include "optchar.h"
int main(void){return 0;}
