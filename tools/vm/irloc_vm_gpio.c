// SPDX-License-Identifier: GPL-2.0
/*
 * make test-vm's LED line: a GPIO chip without hardware behind it, labelled "irloc-vm-leds", with
 * 8 lines that keep the value last set. Debian 13's kernel has neither gpio-mockup nor gpio-sim,
 * and irlocd drives a live camera's LEDs through a GPIO line (tools/test_vm.sh builds this module
 * against the guest kernel's headers).
 */
#include <linux/bitops.h>
#include <linux/gpio/driver.h>
#include <linux/module.h>

static unsigned long irloc_vm_gpio_values;

static int irloc_vm_gpio_get(struct gpio_chip *chip, unsigned int offset)
{
	return test_bit(offset, &irloc_vm_gpio_values);
}

static void irloc_vm_gpio_set(struct gpio_chip *chip, unsigned int offset, int value)
{
	assign_bit(offset, &irloc_vm_gpio_values, value);
}

static int irloc_vm_gpio_direction_output(struct gpio_chip *chip, unsigned int offset, int value)
{
	irloc_vm_gpio_set(chip, offset, value);
	return 0;
}

static int irloc_vm_gpio_get_direction(struct gpio_chip *chip, unsigned int offset)
{
	return GPIO_LINE_DIRECTION_OUT;
}

static struct gpio_chip irloc_vm_gpio_chip = {
	.label = "irloc-vm-leds",
	.owner = THIS_MODULE,
	.base = -1,
	.ngpio = 8,
	.get = irloc_vm_gpio_get,
	.set = irloc_vm_gpio_set,
	.direction_output = irloc_vm_gpio_direction_output,
	.get_direction = irloc_vm_gpio_get_direction,
};

static int __init irloc_vm_gpio_init(void)
{
	return gpiochip_add_data(&irloc_vm_gpio_chip, NULL);
}

static void __exit irloc_vm_gpio_exit(void)
{
	gpiochip_remove(&irloc_vm_gpio_chip);
}

module_init(irloc_vm_gpio_init);
module_exit(irloc_vm_gpio_exit);
MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("GPIO chip without hardware for irloc's make test-vm");
