#include "txtpre.h"
int main(void){return 0;}
