/* The firmware's setup and loop, kept out of the .ino so the host compile check covers them. */
#ifndef DUE_MAIN_H
#define DUE_MAIN_H

void due_main_setup(void);
void due_main_loop(void);

#endif /* DUE_MAIN_H */
