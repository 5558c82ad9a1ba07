#include "txtconst.h"
int main(void){return 0;}
